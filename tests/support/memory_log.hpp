#pragma once
// A stdio stream held in memory, for code that logs to a FILE*: what it wrote, as text.

#include <cstdio>
#include <cstdlib>
#include <string>

namespace irloc::test {

class MemoryLog {
 public:
  MemoryLog() : file_(::open_memstream(&text_, &size_)) {}
  ~MemoryLog() {
    std::fclose(file_);
    std::free(text_);
  }
  MemoryLog(const MemoryLog&) = delete;
  MemoryLog& operator=(const MemoryLog&) = delete;

  std::FILE* file() { return file_; }
  std::string text() {
    std::fflush(file_);
    return std::string(text_, size_);
  }

 private:
  char* text_ = nullptr;
  std::size_t size_ = 0;
  std::FILE* file_;
};

}  // namespace irloc::test
