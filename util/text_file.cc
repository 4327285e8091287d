#include "util/text_file.h"

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <sstream>

#include "util/regular_file.h"

namespace sfm {

Status CheckPlainText(const std::string& path, const std::string& text) {
  auto starts_with = [&](const char* bytes, size_t n) {
    return text.size() >= n && text.compare(0, n, bytes, n) == 0;
  };
  if (starts_with("\xEF\xBB\xBF", 3)) {
    return Status::Error(path +
                         ": starts with a UTF-8 byte-order mark; save it as UTF-8 without BOM (or ASCII)");
  }
  if (starts_with("\xFF\xFE", 2) || starts_with("\xFE\xFF", 2) ||
      (text.size() >= 2 && (text[0] == '\0') != (text[1] == '\0'))) {
    return Status::Error(path + ": is UTF-16 encoded; save it as UTF-8 (or ASCII)");
  }
  const size_t nul = text.find('\0');
  if (nul != std::string::npos) {
    const long line = 1 + std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(nul), '\n');
    return Status::Error(path + ":" + std::to_string(line) +
                         ": holds a NUL byte; a text file cannot hold one");
  }
  for (size_t cr = text.find('\r'); cr != std::string::npos; cr = text.find('\r', cr + 1)) {
    if (cr + 1 == text.size() || text[cr + 1] != '\n') {
      const bool cr_only = text.find('\n') == std::string::npos;
      const long line = 1 + std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(cr), '\n');
      return Status::Error(
          cr_only
              ? path + ": has CR-only line endings (classic Mac OS); save it with LF or CR LF line endings"
              : path + ":" + std::to_string(line) +
                    ": a CR not followed by LF (mixed line endings); save it with LF or CR LF line endings");
    }
  }
  return Status::Ok();
}

Status ReadDataLines(const std::string& path, std::vector<DataLine>* lines) {
  lines->clear();
  std::string text;
  SFM_RETURN_IF_ERROR(ReadRegularFile(path, "file", &text));
  SFM_RETURN_IF_ERROR(CheckPlainText(path, text));
  std::istringstream in(text);
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    const size_t comment = line.find('#');
    if (comment != std::string::npos) line.resize(comment);
    if (line.find_first_not_of(" \t\r\n\v\f") == std::string::npos) continue;
    lines->push_back({number, path + ":" + std::to_string(number) + ": ", line});
  }
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
