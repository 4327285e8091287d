#include "frontend/junctions/junctions_json.h"

#include <glog/logging.h>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <string_view>
#include <utility>
#include <vector>

#include "util/json_format.h"

namespace sfm {
namespace {

// ---- Writing -------------------------------------------------------------------------------------

void AppendFixed(double value, std::string* out) {
  CHECK(std::isfinite(value)) << "junctions JSON: non-finite number";
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value, std::chars_format::fixed, 3);
  out->append(buffer, result.ptr);
}

void AppendGeneral(double value, std::string* out) {
  CHECK(std::isfinite(value)) << "junctions JSON: non-finite number";
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value, std::chars_format::general, 6);
  out->append(buffer, result.ptr);
}

// JsonString keeps the file valid JSON for any bytes (an image path that is not UTF-8 included).
void AppendString(const std::string& value, std::string* out) { out->append(JsonString(value)); }

// ---- Reading: a small JSON parser (RFC 8259 values), enough for this file's fixed shape ----------

struct Value {
  enum class Kind { kNull, kBool, kNumber, kString, kArray, kObject };
  Kind kind = Kind::kNull;
  bool boolean = false;
  double number = 0;
  std::string string;
  std::vector<Value> array;
  std::vector<std::pair<std::string, Value>> object;

  // The member named key of an object, or nullptr.
  const Value* Find(const std::string& key) const {
    for (const auto& [name, value] : object) {
      if (name == key) return &value;
    }
    return nullptr;
  }
};

class Parser {
 public:
  explicit Parser(const std::string& text) : text_(text) {}

  // Parses the whole text as one value; on failure, error() says where and what.
  bool Parse(Value* value) {
    if (!ParseValue(value, 0)) return false;
    SkipSpace();
    return pos_ == text_.size() || Fail("unexpected text after the end");
  }
  const std::string& error() const { return error_; }

 private:
  // Nesting deeper than this is no junctions file; the limit keeps recursion bounded.
  static constexpr int kMaxDepth = 32;

  bool Fail(const std::string& what) {
    error_ = "offset " + std::to_string(pos_) + ": " + what;
    return false;
  }
  void SkipSpace() {
    while (pos_ < text_.size() &&
           (text_[pos_] == ' ' || text_[pos_] == '\n' || text_[pos_] == '\r' || text_[pos_] == '\t')) {
      ++pos_;
    }
  }
  bool Consume(char c) {
    SkipSpace();
    if (pos_ < text_.size() && text_[pos_] == c) {
      ++pos_;
      return true;
    }
    return false;
  }
  bool ConsumeWord(const char* word) {
    const std::string w(word);
    if (text_.compare(pos_, w.size(), w) != 0) return false;
    pos_ += w.size();
    return true;
  }

  bool ParseValue(Value* value, int depth) {
    if (depth > kMaxDepth) return Fail("nested too deeply");
    SkipSpace();
    if (pos_ >= text_.size()) return Fail("unexpected end");
    const char c = text_[pos_];
    if (c == '{') return ParseObject(value, depth);
    if (c == '[') return ParseArray(value, depth);
    if (c == '"') {
      value->kind = Value::Kind::kString;
      return ParseString(&value->string);
    }
    if (ConsumeWord("true") || ConsumeWord("false")) {
      value->kind = Value::Kind::kBool;
      value->boolean = c == 't';
      return true;
    }
    if (ConsumeWord("null")) {
      value->kind = Value::Kind::kNull;
      return true;
    }
    value->kind = Value::Kind::kNumber;
    return ParseNumber(&value->number);
  }

  bool ParseObject(Value* value, int depth) {
    value->kind = Value::Kind::kObject;
    ++pos_;  // '{'
    if (Consume('}')) return true;
    do {
      SkipSpace();
      std::string key;
      if (pos_ >= text_.size() || text_[pos_] != '"') return Fail("expected a key string");
      if (!ParseString(&key)) return false;
      if (!Consume(':')) return Fail("expected ':'");
      value->object.emplace_back(std::move(key), Value());
      if (!ParseValue(&value->object.back().second, depth + 1)) return false;
    } while (Consume(','));
    return Consume('}') || Fail("expected ',' or '}'");
  }

  bool ParseArray(Value* value, int depth) {
    value->kind = Value::Kind::kArray;
    ++pos_;  // '['
    if (Consume(']')) return true;
    do {
      value->array.emplace_back();
      if (!ParseValue(&value->array.back(), depth + 1)) return false;
    } while (Consume(','));
    return Consume(']') || Fail("expected ',' or ']'");
  }

  bool ParseNumber(double* number) {
    const size_t start = pos_;
    while (pos_ < text_.size() &&
           std::string_view("+-0123456789.eE").find(text_[pos_]) != std::string::npos) {
      ++pos_;
    }
    if (start == pos_) return Fail("expected a value");
    const char* first = text_.data() + start;
    const char* last = text_.data() + pos_;
    const auto result = std::from_chars(first, last, *number);
    if (result.ec != std::errc() || result.ptr != last) {
      pos_ = start;
      return Fail("malformed number");
    }
    return true;
  }

  // Four hex digits of a \u escape.
  bool ParseHex4(unsigned* code) {
    if (pos_ + 4 > text_.size()) return Fail("short \\u escape");
    const auto result = std::from_chars(text_.data() + pos_, text_.data() + pos_ + 4, *code, 16);
    if (result.ec != std::errc() || result.ptr != text_.data() + pos_ + 4) return Fail("bad \\u escape");
    pos_ += 4;
    return true;
  }

  static void AppendUtf8(unsigned code, std::string* out) {
    if (code < 0x80) {
      out->push_back(static_cast<char>(code));
    } else if (code < 0x800) {
      out->push_back(static_cast<char>(0xC0 | (code >> 6)));
      out->push_back(static_cast<char>(0x80 | (code & 0x3F)));
    } else if (code < 0x10000) {
      out->push_back(static_cast<char>(0xE0 | (code >> 12)));
      out->push_back(static_cast<char>(0x80 | ((code >> 6) & 0x3F)));
      out->push_back(static_cast<char>(0x80 | (code & 0x3F)));
    } else {
      out->push_back(static_cast<char>(0xF0 | (code >> 18)));
      out->push_back(static_cast<char>(0x80 | ((code >> 12) & 0x3F)));
      out->push_back(static_cast<char>(0x80 | ((code >> 6) & 0x3F)));
      out->push_back(static_cast<char>(0x80 | (code & 0x3F)));
    }
  }

  bool ParseString(std::string* out) {
    ++pos_;  // opening quote
    while (pos_ < text_.size()) {
      const char c = text_[pos_++];
      if (c == '"') return true;
      if (static_cast<unsigned char>(c) < 0x20) return Fail("control character in a string");
      if (c != '\\') {
        out->push_back(c);
        continue;
      }
      if (pos_ >= text_.size()) break;
      const char e = text_[pos_++];
      switch (e) {
        case '"':
        case '\\':
        case '/':
          out->push_back(e);
          break;
        case 'b':
          out->push_back('\b');
          break;
        case 'f':
          out->push_back('\f');
          break;
        case 'n':
          out->push_back('\n');
          break;
        case 'r':
          out->push_back('\r');
          break;
        case 't':
          out->push_back('\t');
          break;
        case 'u': {
          unsigned code = 0;
          if (!ParseHex4(&code)) return false;
          if (code >= 0xD800 && code < 0xDC00) {  // high surrogate: a low one must follow
            unsigned low = 0;
            if (!ConsumeWord("\\u") || !ParseHex4(&low) || low < 0xDC00 || low >= 0xE000) {
              return Fail("unpaired surrogate in \\u escape");
            }
            code = 0x10000 + ((code - 0xD800) << 10) + (low - 0xDC00);
          }
          AppendUtf8(code, out);
          break;
        }
        default:
          return Fail("bad escape in a string");
      }
    }
    return Fail("unterminated string");
  }

  const std::string& text_;
  size_t pos_ = 0;
  std::string error_;
};

// ---- The file's shape ----------------------------------------------------------------------------

// Reads shape checks into one message: "<what>: <problem>".
class ShapeReader {
 public:
  bool Number(const Value& object, const char* key, const std::string& where, double* out) {
    const Value* value = object.Find(key);
    if (value == nullptr || value->kind != Value::Kind::kNumber) {
      return Fail(where + "\"" + key + "\" missing or not a number");
    }
    *out = value->number;
    return true;
  }
  bool Integer(const Value& object, const char* key, const std::string& where, int* out) {
    double number = 0;
    if (!Number(object, key, where, &number)) return false;
    if (number != std::floor(number) || std::abs(number) > 2e9) {
      return Fail(where + "\"" + key + "\" is not an integer");
    }
    *out = static_cast<int>(number);
    return true;
  }
  bool Fail(const std::string& message) {
    error = message;
    return false;
  }
  std::string error;
};

bool ReadJunction(const Value& value, const std::string& where, ShapeReader* reader, Junction* junction) {
  if (value.kind != Value::Kind::kObject) return reader->Fail(where + "not an object");
  if (!reader->Integer(value, "id", where, &junction->id) ||
      !reader->Number(value, "x", where, &junction->location.x()) ||
      !reader->Number(value, "y", where, &junction->location.y()) ||
      !reader->Number(value, "score", where, &junction->score)) {
    return false;
  }
  const Value* type = value.Find("type");
  if (type == nullptr || type->kind != Value::Kind::kString) {
    return reader->Fail(where + "\"type\" missing or not a string");
  }
  bool known = false;
  for (JunctionType t : {JunctionType::kL, JunctionType::kY, JunctionType::kArrow, JunctionType::kT,
                         JunctionType::kX, JunctionType::kN}) {
    if (type->string == JunctionTypeName(t)) {
      junction->type = t;
      known = true;
    }
  }
  if (!known) return reader->Fail(where + "unknown type \"" + type->string + "\"");
  const Value* segments = value.Find("segments");
  if (segments == nullptr || segments->kind != Value::Kind::kArray) {
    return reader->Fail(where + "\"segments\" missing or not an array");
  }
  for (const Value& point : segments->array) {
    if (point.kind != Value::Kind::kArray || point.array.size() != 2 ||
        point.array[0].kind != Value::Kind::kNumber || point.array[1].kind != Value::Kind::kNumber) {
      return reader->Fail(where + "a segment end-point is not [x, y]");
    }
    JunctionSegment segment;
    segment.end = Eigen::Vector2d(point.array[0].number, point.array[1].number);
    junction->segments.push_back(segment);
  }
  return true;
}

}  // namespace

std::string JunctionsToJson(int frame, const std::string& image, int width, int height,
                            const Junctions& junctions) {
  std::string out = "{\"frame\": " + std::to_string(frame) + ", \"image\": ";
  AppendString(image, &out);
  out += ", \"width\": " + std::to_string(width) + ", \"height\": " + std::to_string(height) + ",\n";
  out += " \"junctions\": [";
  for (size_t j = 0; j < junctions.size(); ++j) {
    const Junction& junction = junctions[j];
    out += j == 0 ? "\n   " : ",\n   ";
    out += "{\"id\": " + std::to_string(junction.id) + ", \"x\": ";
    AppendFixed(junction.location.x(), &out);
    out += ", \"y\": ";
    AppendFixed(junction.location.y(), &out);
    out += ", \"type\": \"";
    out += JunctionTypeName(junction.type);
    out += "\", \"score\": ";
    AppendGeneral(junction.score, &out);
    out += ",\n    \"segments\": [";
    for (size_t i = 0; i < junction.segments.size(); ++i) {
      out += i == 0 ? "[" : ", [";
      AppendFixed(junction.segments[i].end.x(), &out);
      out += ", ";
      AppendFixed(junction.segments[i].end.y(), &out);
      out += "]";
    }
    out += "]}";
  }
  out += junctions.empty() ? "]}\n" : "\n ]}\n";
  return out;
}

Status JunctionsFromJson(const std::string& json, const std::string& source, JunctionsFile* file) {
  Value root;
  Parser parser(json);
  if (!parser.Parse(&root)) return Status::Error(source + ": " + parser.error());
  if (root.kind != Value::Kind::kObject) return Status::Error(source + ": not a JSON object");
  ShapeReader reader;
  JunctionsFile result;
  const Value* image = root.Find("image");
  if (!reader.Integer(root, "frame", "", &result.frame) ||
      !reader.Integer(root, "width", "", &result.width) ||
      !reader.Integer(root, "height", "", &result.height)) {
    return Status::Error(source + ": " + reader.error);
  }
  if (image == nullptr || image->kind != Value::Kind::kString) {
    return Status::Error(source + ": \"image\" missing or not a string");
  }
  result.image = image->string;
  const Value* junctions = root.Find("junctions");
  if (junctions == nullptr || junctions->kind != Value::Kind::kArray) {
    return Status::Error(source + ": \"junctions\" missing or not an array");
  }
  for (size_t j = 0; j < junctions->array.size(); ++j) {
    Junction junction;
    if (!ReadJunction(junctions->array[j], "junctions[" + std::to_string(j) + "]: ", &reader, &junction)) {
      return Status::Error(source + ": " + reader.error);
    }
    result.junctions.push_back(std::move(junction));
  }
  *file = std::move(result);
  return Status::Ok();
}

}  // namespace sfm
