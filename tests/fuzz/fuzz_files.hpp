#pragma once
// The entry point every target defines, and the files the parsers under fuzzing read: each input is written to a file in one temporary folder
// per process (made on first use, next to the valid files a target needs), and the reader is
// given its path. An InputError is the expected answer to a bad file; anything else escaping a
// reader (another exception, a crash, a sanitizer report, a hang) is a finding.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

// The entry point of every target (libFuzzer's, or replay_main.cpp's loop over a corpus).
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace irloc::fuzz {

// The process's temporary folder.
const std::filesystem::path& folder();

// Writes `size` bytes to folder()/name and returns its path.
std::filesystem::path write_file(const std::string& name, const std::uint8_t* data, std::size_t size);
std::filesystem::path write_file(const std::string& name, const std::string& text);

// Reads the dataset in folder() (frames.csv and its frames, calibrated width x height) with the
// `dir:` camera to its end; an InputError ends it.
void replay_dataset(int width, int height);

}  // namespace irloc::fuzz
