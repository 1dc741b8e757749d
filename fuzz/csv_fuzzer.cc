// The CSV reader (common/csv.h): force–penetration data and time series.
#include "common/csv.h"
#include "fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size)
{
  using namespace clearjoint;
  fuzz::expect_only_input_errors([&] {
    const CsvTable t = parse_csv(fuzz::text_of(data, size), "fuzz.csv");
    // What fit_stage does next: look up its columns.
    if (t.has_column("delta") && t.has_column("force"))
      (void)t.column("force");
  });
  return 0;
}
