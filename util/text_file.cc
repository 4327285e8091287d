#include "util/text_file.h"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace sfm {

Status ReadDataLines(const std::string& path, std::vector<DataLine>* lines) {
  lines->clear();
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) return Status::Error(path + ": is a directory, expected a file");
  if (!std::filesystem::exists(path, error)) return Status::Error(path + ": file does not exist");
  std::ifstream in(path);
  if (!in) return Status::Error(path + ": cannot open (" + std::strerror(errno) + ")");
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    const size_t comment = line.find('#');
    if (comment != std::string::npos) line.resize(comment);
    if (line.find_first_not_of(" \t\r\n\v\f") == std::string::npos) continue;
    lines->push_back({number, path + ":" + std::to_string(number) + ": ", line});
  }
  if (in.bad()) return Status::Error(path + ": read error (" + std::strerror(errno) + ")");
  return Status::Ok();
}

std::vector<std::string> SplitWords(const std::string& text) {
  std::istringstream stream(text);
  std::vector<std::string> words;
  for (std::string word; stream >> word;) words.push_back(word);
  return words;
}

bool ParseDouble(const std::string& token, double* value) {
  errno = 0;
  char* end = nullptr;
  *value = std::strtod(token.c_str(), &end);
  return end != token.c_str() && *end == '\0' && errno != ERANGE;
}

}  // namespace sfm
