// The law-file and law-family readers (clearjoint.law/1, clearjoint.law_family/1), JSON.
#include "common/document_reader.h"
#include "fuzz/fuzz_support.h"
#include "laws/law_family.h"
#include "laws/law_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size)
{
  using namespace clearjoint;
  fuzz::expect_only_input_errors([&] {
    const auto j = parse_json_string(fuzz::text_of(data, size), "fuzz.json");
    if (j.is_object() && j.contains("members"))
      laws::law_family_from_json(j, "fuzz.json");
    else
      laws::law_from_json(j, "fuzz.json");
  });
  return 0;
}
