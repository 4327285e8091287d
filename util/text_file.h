// Reading the project's line-oriented text inputs (images.txt, TUM trajectories, data-set files):
// one place for comments, line numbers in messages, and strict number parsing.
#pragma once

#include <string>
#include <vector>

#include "util/status.h"

namespace sfm {

// A line holding data: its 1-based number, "path:number: " for messages, and its text with any
// '#' comment cut off.
struct DataLine {
  int number = 0;
  std::string where;
  std::string text;
};

// The lines of `path` that hold more than white space once a '#' comment is cut. Fails, naming the
// file, when it is missing, is not a regular file (ReadRegularFile: never blocks on a FIFO), cannot
// be read, or is not plain text (CheckPlainText).
Status ReadDataLines(const std::string& path, std::vector<DataLine>* lines);

// OK when `text` (the contents of `path`) is plain 8-bit text with LF or CR LF line endings;
// otherwise a message naming the problem: a UTF-8 byte-order mark, UTF-16, a NUL byte (with its
// line), CR-only or mixed line endings.
Status CheckPlainText(const std::string& path, const std::string& text);

// The white-space separated words of `text`.
std::vector<std::string> SplitWords(const std::string& text);

// Parses the whole of `token` as a double (no trailing characters, no overflow). Non-finite
// spellings ("nan", "inf") parse: callers that need finite numbers check std::isfinite.
bool ParseDouble(const std::string& token, double* value);

}  // namespace sfm
