#include "sequences/importers/input_files.h"

#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include <glog/logging.h>
#include <opencv2/imgcodecs.hpp>

#include "util/text_file.h"

namespace sfm {
namespace {

// While alive, whatever is written to file descriptor 2 (std::cerr, C stdio, OpenCV's logger)
// goes to a temporary file instead; Release() restores stderr and returns the text.
class StderrCapture {
 public:
  StderrCapture() {
    std::fflush(stderr);
    std::cerr.flush();
    file_ = std::tmpfile();
    saved_ = file_ != nullptr ? ::dup(2) : -1;
    if (saved_ >= 0) ::dup2(::fileno(file_), 2);
  }
  StderrCapture(const StderrCapture&) = delete;
  StderrCapture& operator=(const StderrCapture&) = delete;
  ~StderrCapture() { Release(); }

  std::string Release() {
    std::string text;
    if (saved_ < 0) {
      if (file_ != nullptr) std::fclose(file_);
      file_ = nullptr;
      return text;
    }
    std::fflush(stderr);
    std::cerr.flush();
    ::dup2(saved_, 2);
    ::close(saved_);
    saved_ = -1;
    std::rewind(file_);
    char buffer[512];
    size_t read = 0;
    while ((read = std::fread(buffer, 1, sizeof(buffer), file_)) > 0 && text.size() < 4096) text.append(buffer, read);
    std::fclose(file_);
    file_ = nullptr;
    return text;
  }

 private:
  std::FILE* file_ = nullptr;
  int saved_ = -1;
};

// The captured text as one line: OpenCV's messages span lines and end in blank ones.
std::string OneLine(std::string text) {
  for (char& c : text) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  const size_t end = text.find_last_not_of(' ');
  return end == std::string::npos ? std::string() : text.substr(0, end + 1);
}

}  // namespace

Status ReadNumbers(const std::string& path, std::vector<double>* numbers) {
  numbers->clear();
  std::vector<DataLine> lines;
  SFM_RETURN_IF_ERROR(ReadDataLines(path, &lines));
  for (const DataLine& line : lines) {
    for (const std::string& token : SplitWords(line.text)) {
      double value = 0;
      if (!ParseDouble(token, &value) || !std::isfinite(value)) {
        return Status::Error(line.where + "'" + token + "' is not a finite number");
      }
      numbers->push_back(value);
    }
  }
  return Status::Ok();
}

namespace {

// cv::imread or cv::imdecode by `decode`, with the codecs' diagnostics caught (see DecodeImage).
template <typename Decode>
Status DecodeCaptured(const std::string& where, const Decode& decode, cv::Mat* image) {
  StderrCapture capture;
  cv::Mat decoded;
  std::string exception;
  try {
    decoded = decode();
  } catch (const cv::Exception& e) {
    exception = e.what();
  }
  const std::string diagnostics = OneLine(capture.Release() + exception);
  if (decoded.empty()) {
    return Status::Error(where + ": cannot decode image" +
                         (diagnostics.empty() ? "" : " (" + diagnostics + ")"));
  }
  if (diagnostics.find("Premature end of JPEG file") != std::string::npos) {
    return Status::Error(where + ": cannot decode image (truncated: " + diagnostics + ")");
  }
  if (!diagnostics.empty()) LOG(WARNING) << where << ": " << diagnostics;
  *image = decoded;
  return Status::Ok();
}

}  // namespace

Status DecodeImage(const std::string& path, int flags, cv::Mat* image) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error))
    return Status::Error(path + ": image file does not exist");
  return DecodeCaptured(
      path, [&] { return cv::imread(path, flags); }, image);
}

Status DecodeImageBytes(const std::string& where, const std::vector<unsigned char>& bytes, int flags,
                        cv::Mat* image) {
  if (bytes.empty()) return Status::Error(where + ": cannot decode image (no data)");
  return DecodeCaptured(
      where, [&] { return cv::imdecode(bytes, flags); }, image);
}

}  // namespace sfm
