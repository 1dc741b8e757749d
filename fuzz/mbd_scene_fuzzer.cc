// mbd_stage's scene reader (schema clearjoint.mbd/1), YAML, with law files resolved against the
// shipped scenes' folder so that the seeds reach the law readers too.
#include "fuzz/fuzz_support.h"
#include "mbd_stage/scene.h"
#include "common/document_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size)
{
  using namespace clearjoint;
  fuzz::expect_only_input_errors([&] {
    const auto j = parse_yaml_string(fuzz::text_of(data, size), "fuzz.yaml");
    mbd::scene_from_json(j, "fuzz.yaml", CLEARJOINT_SOURCE_DIR "/mbd_stage/scenes");
  });
  return 0;
}
