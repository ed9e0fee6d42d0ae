#include "tests/fuzz/fuzz_files.hpp"

#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <stdexcept>

#include "io/input_error.hpp"
#include "hal/replay/dataset_camera.hpp"

namespace irloc::fuzz {

namespace {

// Made on first use, removed when the process exits normally (libFuzzer's time limit included).
class TemporaryFolder {
 public:
  TemporaryFolder() {
    std::string pattern = (std::filesystem::temp_directory_path() / "irloc-fuzz-XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("cannot make a temporary folder");
    path_ = pattern;
  }
  ~TemporaryFolder() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  TemporaryFolder(const TemporaryFolder&) = delete;
  TemporaryFolder& operator=(const TemporaryFolder&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace

const std::filesystem::path& folder() {
  static const TemporaryFolder temporary;
  return temporary.path();
}

std::filesystem::path write_file(const std::string& name, const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path path = folder() / name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  if (!out.flush()) throw std::runtime_error("cannot write " + path.string());
  return path;
}

std::filesystem::path write_file(const std::string& name, const std::string& text) {
  return write_file(name, reinterpret_cast<const std::uint8_t*>(text.data()), text.size());
}

void replay_dataset(int width, int height) {
  try {
    hal::DatasetCamera camera(folder(), width, height, "calib.yaml");
    Frame frame;
    while (camera.next(frame)) {
    }
  } catch (const io::InputError&) {
  }
}

}  // namespace irloc::fuzz
