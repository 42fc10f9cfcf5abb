#include "io/json_source.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>

#include "core/hash.h"
#include "core/unit_vector.h"

namespace glint {

namespace {

using nlohmann::json;

// An input iterator that counts the characters nlohmann's lexer has consumed, so the SAX
// callbacks below know where in the text they are.
struct CountingIterator {
  using iterator_category = std::input_iterator_tag;
  using value_type = char;
  using difference_type = std::ptrdiff_t;
  using pointer = const char*;
  using reference = const char&;

  const char* p = nullptr;
  size_t* consumed = nullptr;

  reference operator*() const { return *p; }
  CountingIterator& operator++() {
    ++p;
    ++*consumed;
    return *this;
  }
  CountingIterator operator++(int) {
    CountingIterator old = *this;
    ++*this;
    return old;
  }
  bool operator==(const CountingIterator& o) const { return p == o.p; }
  bool operator!=(const CountingIterator& o) const { return p != o.p; }
};

std::string escapePointerToken(const std::string& key) {
  std::string out;
  for (char c : key) {
    if (c == '~')
      out += "~0";
    else if (c == '/')
      out += "~1";
    else
      out += c;
  }
  return out;
}

// A scene nests at most 8 deep (groups.NAME[i].motion.positions[k][v]); far deeper input is a
// mistake or an attack, and nlohmann's dump() in error messages recurses once per level.
constexpr size_t kMaxNesting = 64;
// Every JsonNode carries its path, keys included, and arrays are expanded into nodes at once, so
// a group name of 200 kB over 8000 motion keys took 4 GB. Names need nothing like this length.
constexpr size_t kMaxKeyLength = 256;

// Lines are keyed by a hash of the JSON pointer, extended token by token, so the map grows with
// the number of values and not with their depth or key lengths (whole pointer strings made
// 80 kB of nested brackets cost 2 GB).
constexpr uint64_t kRootPointer = 0;
uint64_t childPointer(uint64_t parent, std::string_view escapedToken) {
  return hashCombine(parent, hashBytes(escapedToken));
}

// Records the line of every key and array element. nlohmann calls each callback right after
// scanning the token it reports (numbers read one character ahead), so the last consumed
// character lies on the token's line.
class LineRecorder : public nlohmann::json_sax<json> {
 public:
  LineRecorder(const std::vector<size_t>& lineStarts, const size_t& consumed,
               std::unordered_map<uint64_t, int>& lines)
      : lineStarts_(lineStarts), consumed_(consumed), lines_(lines) {}

  // What exceeded kMaxNesting or kMaxKeyLength and its line; empty and 0 if nothing did.
  const std::string& limitProblem() const { return limitProblem_; }
  int limitLine() const { return limitLine_; }

  bool null() override { return scalar(1); }
  bool boolean(bool) override { return scalar(1); }
  bool number_integer(number_integer_t) override { return scalar(2); }
  bool number_unsigned(number_unsigned_t) override { return scalar(2); }
  bool number_float(number_float_t, const string_t&) override { return scalar(2); }
  bool string(string_t&) override { return scalar(1); }
  bool binary(binary_t&) override { return scalar(1); }
  bool start_object(std::size_t) override { return startContainer(false); }
  bool end_object() override { return endContainer(); }
  bool start_array(std::size_t) override { return startContainer(true); }
  bool end_array() override { return endContainer(); }
  bool key(string_t& k) override {
    if (k.size() > kMaxKeyLength)
      return stop("a key is " + std::to_string(k.size()) + " characters long; keys and names " +
                  "may have at most " + std::to_string(kMaxKeyLength));
    stack_.back().key = childPointer(stack_.back().pointer, escapePointerToken(k));
    // nlohmann keeps the last of duplicate keys; a scene that says two things is refused.
    const auto [first, isNew] = lines_.emplace(stack_.back().key, lineNow(1));
    if (!isNew)
      return stop("duplicate key " + inQuotes(k) + " (first on line " +
                  std::to_string(first->second) + "): a key may appear once in an object");
    return true;
  }
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override {
    return false;
  }

 private:
  struct Frame {
    bool isArray;
    size_t index;
    uint64_t key;  // pointer of the current member, in objects
    uint64_t pointer;
  };

  int lineNow(size_t back) const {
    const size_t offset = consumed_ >= back ? consumed_ - back : 0;
    const auto it = std::upper_bound(lineStarts_.begin(), lineStarts_.end(), offset);
    return static_cast<int>(it - lineStarts_.begin());
  }
  uint64_t beginValue(size_t back) {
    if (stack_.empty()) {
      lines_.emplace(kRootPointer, lineNow(back));
      return kRootPointer;
    }
    Frame& top = stack_.back();
    if (!top.isArray) return top.key;
    const uint64_t ptr = childPointer(top.pointer, std::to_string(top.index++));
    lines_.emplace(ptr, lineNow(back));
    return ptr;
  }
  bool startContainer(bool isArray) {
    if (stack_.size() >= kMaxNesting)
      return stop("arrays and objects nest more than " + std::to_string(kMaxNesting) +
                  " deep (a scene needs at most 8)");
    stack_.push_back({isArray, 0, 0, beginValue(1)});
    return true;
  }
  bool stop(std::string problem) {
    limitProblem_ = std::move(problem);
    limitLine_ = lineNow(1);
    return false;  // ends the parse
  }
  bool scalar(size_t back) {
    beginValue(back);
    return true;
  }
  bool endContainer() {
    stack_.pop_back();
    return true;
  }

  const std::vector<size_t>& lineStarts_;
  const size_t& consumed_;
  std::unordered_map<uint64_t, int>& lines_;
  std::vector<Frame> stack_;
  std::string limitProblem_;
  int limitLine_ = 0;
};

std::string joinPath(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

}  // namespace

std::string formatNumber(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

JsonDocument::JsonDocument(const std::string& text, std::string fileName)
    : fileName_(std::move(fileName)) {
  // Lines end at LF, CR LF, or a lone CR (old Mac files), as editors count them.
  std::vector<size_t> lineStarts{0};
  for (size_t i = 0; i < text.size(); ++i)
    if (text[i] == '\n' || (text[i] == '\r' && (i + 1 == text.size() || text[i + 1] != '\n')))
      lineStarts.push_back(i + 1);
  const auto lineOfOffset = [&](size_t offset) {
    return static_cast<int>(std::upper_bound(lineStarts.begin(), lineStarts.end(), offset) -
                            lineStarts.begin());
  };
  try {
    root_ = json::parse(text, nullptr, true, /*ignore_comments=*/true);
  } catch (const json::parse_error& e) {
    // e.byte is 1-based and points just past the offending character.
    const size_t offset = e.byte > 0 ? e.byte - 1 : 0;
    std::string what = e.what();
    const auto colon = what.find("syntax error");
    throw SceneError({fileName_, lineOfOffset(offset)}, "",
                     "invalid JSON: " + (colon != std::string::npos ? what.substr(colon) : what));
  } catch (const json::out_of_range& e) {
    // nlohmann refuses numbers beyond double range ("number overflow parsing '1e999'") without
    // a position; find the literal in the text to name its line.
    const std::string what = e.what();
    const auto open = what.find('\''), close = what.rfind('\'');
    const std::string literal =
        open != std::string::npos && close > open ? what.substr(open + 1, close - open - 1) : "";
    const size_t at = literal.empty() ? std::string::npos : text.find(literal);
    throw SceneError({fileName_, at == std::string::npos ? 0 : lineOfOffset(at)}, "",
                     "number " + literal + " is out of range: numbers must be finite");
  }
  size_t consumed = 0;
  LineRecorder recorder(lineStarts, consumed, lines_);
  CountingIterator first{text.data(), &consumed}, last{text.data() + text.size(), &consumed};
  json::sax_parse(first, last, &recorder, nlohmann::detail::input_format_t::json, true, true);
  if (!recorder.limitProblem().empty())
    throw SceneError({fileName_, recorder.limitLine()}, "", recorder.limitProblem());
}

int JsonDocument::lineOf(const std::string& pointer) const {
  // `pointer` is "" (the root) or "/token/token...", tokens escaped as the recorder hashed them.
  uint64_t hash = kRootPointer;
  for (size_t slash = 0; slash < pointer.size();) {
    const size_t next = std::min(pointer.find('/', slash + 1), pointer.size());
    hash = childPointer(hash, std::string_view(pointer).substr(slash + 1, next - slash - 1));
    slash = next;
  }
  const auto it = lines_.find(hash);
  return it == lines_.end() ? 0 : it->second;
}

void JsonNode::fail(const std::string& problem) const { throw SceneError(loc(), path_, problem); }

std::string JsonNode::typeName() const { return value_->type_name(); }

JsonNode JsonNode::child(const nlohmann::json& value, const std::string& key) const {
  return JsonNode(*doc_, value, pointer_ + "/" + escapePointerToken(key), joinPath(path_, key));
}

void JsonNode::checkKeys(std::initializer_list<std::string_view> allowed) const {
  checkKeys(std::vector<std::string>(allowed.begin(), allowed.end()));
}

void JsonNode::checkKeys(const std::vector<std::string>& names) const {
  if (!isObject()) fail("must be an object, got " + typeName());
  for (const auto& item : value_->items()) {
    if (std::find(names.begin(), names.end(), item.key()) != names.end()) continue;
    const std::string hint = nearestName(item.key(), names);
    child(item.value(), item.key())
        .fail("unknown key" + (hint.empty() ? std::string() : " (did you mean \"" + hint + "\"?)"));
  }
}

bool JsonNode::has(const std::string& key) const {
  return value_->is_object() && value_->contains(key);
}

JsonNode JsonNode::at(const std::string& key) const {
  if (!isObject()) fail("must be an object, got " + typeName());
  const auto it = value_->find(key);
  if (it == value_->end()) fail("missing required key " + inQuotes(key));
  return child(*it, key);
}

std::optional<JsonNode> JsonNode::get(const std::string& key) const {
  if (!has(key)) return std::nullopt;
  return child(value_->at(key), key);
}

std::vector<std::string> JsonNode::keys() const {
  if (!isObject()) fail("must be an object, got " + typeName());
  std::vector<std::string> out;
  for (const auto& item : value_->items()) out.push_back(item.key());
  return out;
}

size_t JsonNode::size() const {
  if (!isArray()) fail("must be an array, got " + typeName());
  return value_->size();
}

JsonNode JsonNode::operator[](size_t i) const {
  return JsonNode(*doc_, value_->at(i), pointer_ + "/" + std::to_string(i),
                  path_ + "[" + std::to_string(i) + "]");
}

std::vector<JsonNode> JsonNode::elements() const {
  std::vector<JsonNode> out;
  for (size_t i = 0; i < size(); ++i) out.push_back((*this)[i]);
  return out;
}

double JsonNode::real() const {
  if (!isNumber()) fail("must be a number, got " + typeName());
  const double v = value_->get<double>();
  if (!std::isfinite(v)) fail("must be finite, got " + formatNumber(v));
  if (std::fabs(v) > 3.4e38) fail("is out of the float range, got " + formatNumber(v));
  return v;
}

float JsonNode::number() const { return static_cast<float>(real()); }

float JsonNode::number(float lo, float hi, bool loOpen) const {
  const double exact = real();
  const float v = static_cast<float>(exact);
  // Render threads flush subnormal floats to zero (core/fp_env.h): a value that must be positive
  // must be a normal float, or it is zero where it is used (a marble's scale of 1e-38 divided
  // by zero, every sample NaN).
  if (loOpen && lo == 0 && exact > 0 && !(v >= std::numeric_limits<float>::min()))
    fail("must be >= " + formatNumber(std::numeric_limits<float>::min()) +
         " (the smallest normal float: smaller values are zero to the renderer), got " +
         formatNumber(exact));
  if (loOpen ? !(v > lo) : !(v >= lo))
    fail("must be " + std::string(loOpen ? "> " : ">= ") + formatNumber(lo) + ", got " +
         formatNumber(v));
  if (v > hi) fail("must be <= " + formatNumber(hi) + ", got " + formatNumber(v));
  return v;
}

int JsonNode::integer(int lo, int hi) const {
  if (!value_->is_number_integer()) fail("must be an integer, got " + typeName());
  const std::string range = "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  // Beyond long long (an unsigned literal above 2^63) would wrap if read as signed.
  if (value_->is_number_unsigned() && value_->get<uint64_t>() > uint64_t(hi))
    fail(range + ", got " + std::to_string(value_->get<uint64_t>()));
  const auto v = value_->get<long long>();
  if (v < lo || v > hi) fail(range + ", got " + std::to_string(v));
  return static_cast<int>(v);
}

uint64_t JsonNode::unsignedInteger() const {
  // JSON's -0 is zero; nlohmann reads it as a signed integer.
  if (value_->is_number_integer() && value_->get<int64_t>() == 0) return 0;
  if (!value_->is_number_unsigned())
    fail("must be a non-negative integer, got " + excerpt(raw().dump()));
  return value_->get<uint64_t>();
}

bool JsonNode::boolean() const {
  if (!value_->is_boolean()) fail("must be true or false, got " + typeName());
  return value_->get<bool>();
}

std::string JsonNode::string() const {
  if (!isString()) fail("must be a string, got " + typeName());
  return value_->get<std::string>();
}

std::string JsonNode::choice(std::initializer_list<std::string_view> options) const {
  const std::string s = string();
  std::vector<std::string> names(options.begin(), options.end());
  if (std::find(names.begin(), names.end(), s) != names.end()) return s;
  std::string list;
  for (const auto& n : names) list += (list.empty() ? "\"" : ", \"") + n + "\"";
  const std::string hint = nearestName(s, names);
  fail("must be one of " + list + ", got " + inQuotes(s) +
       (hint.empty() ? "" : " (did you mean \"" + hint + "\"?)"));
}

Vec3d JsonNode::vec3d() const {
  if (!isArray() || value_->size() != 3)
    fail("must be an array of 3 numbers, got " + excerpt(raw().dump()));
  return {(*this)[0].real(), (*this)[1].real(), (*this)[2].real()};
}

Vec3f JsonNode::vec3() const { return toFloat(vec3d()); }

Vec3f JsonNode::direction() const {
  const Vec3d v = vec3d();
  if (v.x == 0 && v.y == 0 && v.z == 0) fail("must be a non-zero vector");
  return unitVector(v);
}

Rgb JsonNode::color() const {
  if (!isArray() || value_->size() != 3)
    fail("must be an RGB triple, got " + excerpt(raw().dump()));
  return {(*this)[0].number(0, 3.4e38f), (*this)[1].number(0, 3.4e38f),
          (*this)[2].number(0, 3.4e38f)};
}

Vec3f JsonNode::vec3(const std::string& key, Vec3f dflt) const {
  const auto n = get(key);
  return n ? n->vec3() : dflt;
}

Rgb JsonNode::color(const std::string& key, Rgb dflt) const {
  const auto n = get(key);
  return n ? n->color() : dflt;
}

std::string nearestName(const std::string& name, const std::vector<std::string>& candidates) {
  std::string best;
  size_t bestDist = std::max<size_t>(2, name.size() / 3) + 1;
  for (const auto& c : candidates) {
    // The distance is at least the difference in length: skip what cannot win (and a 10 MB
    // value's quadratic comparison).
    const size_t lengthGap =
        name.size() > c.size() ? name.size() - c.size() : c.size() - name.size();
    if (lengthGap >= bestDist) continue;
    const size_t d = editDistance(name, c);
    if (d < bestDist) {
      bestDist = d;
      best = c;
    }
  }
  return best;
}

}  // namespace glint
