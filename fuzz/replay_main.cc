// The driver of the fuzz targets in a normal (g++) build: runs LLVMFuzzerTestOneInput once on
// every file named on the command line (or found in a named folder), so the seeds and the
// regression corpus (inputs that once failed) are replayed by every test run. A finding
// aborts the process, and ctest reports the test as failed; the file being replayed is printed
// first so it can be found.
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size);

int main(int argc, char **argv)
{
  namespace fs = std::filesystem;
  std::vector<fs::path> files;
  for (int i = 1; i < argc; ++i)
  {
    const fs::path p(argv[i]);
    if (fs::is_directory(p))
    {
      for (const auto &e : fs::recursive_directory_iterator(p))
        if (e.is_regular_file())
          files.push_back(e.path());
    }
    else if (fs::is_regular_file(p))
      files.push_back(p);
    else
    {
      std::fprintf(stderr, "replay: no such file or folder: %s\n", argv[i]);
      return 2;
    }
  }
  if (files.empty())
  {
    std::fprintf(stderr, "replay: no inputs\n");
    return 2;
  }
  for (const auto &f : files)
  {
    std::fprintf(stderr, "replay: %s\n", f.c_str());
    std::ifstream in(f, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), {});
    LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t *>(bytes.data()), bytes.size());
  }
  std::printf("replay: %zu inputs, no finding\n", files.size());
  return 0;
}
