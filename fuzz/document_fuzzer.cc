// The common YAML/JSON reading path (common/document_reader.h): the first byte picks the
// format, the rest is the document.
#include "common/document_reader.h"
#include "fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size)
{
  using namespace clearjoint;
  if (size == 0)
    return 0;
  const std::string text = fuzz::text_of(data + 1, size - 1);
  fuzz::expect_only_input_errors([&] {
    const nlohmann::json j = (data[0] & 1) ? parse_json_string(text, "fuzz.json")
                                           : parse_yaml_string(text, "fuzz.yaml");
    // What the stages do with a document: dump it into messages and summaries.
    (void)json_excerpt(j);
    (void)j.dump();
  });
  return 0;
}
