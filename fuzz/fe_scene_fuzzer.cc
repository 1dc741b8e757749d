// fe_stage's scene reader (schema clearjoint.fe/1), YAML; the reader has no deal.II.
#include "common/document_reader.h"
#include "fe_stage/scene.h"
#include "fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size)
{
  using namespace clearjoint;
  fuzz::expect_only_input_errors([&] {
    const auto j = parse_yaml_string(fuzz::text_of(data, size), "fuzz.yaml");
    fe::scene_from_json(j, CLEARJOINT_SOURCE_DIR "/fe_stage/scenes/fuzz.yaml");
  });
  return 0;
}
