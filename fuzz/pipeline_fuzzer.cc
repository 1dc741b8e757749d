// run_pipeline's reader (clearjoint.pipeline/1). It reads a path, so each input is written to
// a file of this process first; relative scene paths resolve from the source tree, where the
// seeds' scenes exist.
#include "fuzz/fuzz_support.h"
#include "pipeline/pipeline_config.h"
#include "pipeline/sweep_values.h"

#include <unistd.h>

#include <fstream>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size)
{
  using namespace clearjoint;
  static const bool in_source = ::chdir(CLEARJOINT_SOURCE_DIR) == 0;
  (void)in_source;
  struct TempFile
  {
    std::string path = "/tmp/clearjoint-fuzz-pipeline-" + std::to_string(::getpid()) + ".yaml";
    ~TempFile() { ::unlink(path.c_str()); }
  };
  static const TempFile file;
  const std::string &path = file.path;
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char *>(data), static_cast<std::streamsize>(size));
  }
  fuzz::expect_only_input_errors([&] {
    auto config = pipeline::read_pipeline_config(path);
    pipeline::resolve_value_keywords(config);
  });
  return 0;
}
