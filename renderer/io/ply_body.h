#pragma once
// The body of a PLY file as values, for io/ply_reader.cpp: the file read through a fixed
// buffer, and its binary (either byte order) or ASCII values, each checked as it is read. A
// problem is thrown as ply::Bad; the reader adds the file, element and property to it.
#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <string_view>

#include "core/error.h"
#include "io/ply_header.h"

namespace glint::ply {

// The body is read through a buffer of this size, whatever the file's.
inline constexpr size_t kBufferBytes = size_t{1} << 20;
// An ASCII value longer than this is refused: no number needs it, and a token must fit the
// buffer to be parsed in place.
inline constexpr size_t kMaxTokenChars = 256;

// A problem with the value just read; the element loop adds the file and the element's place.
struct Bad {
  std::string what;
};

// The file from the body's first byte, through a fixed buffer: binary values by size, ASCII
// values by whitespace-separated token.
class Body {
 public:
  // `firstLine`: the file's line number of the body's first line.
  Body(const std::string& path, uint64_t start, uint64_t fileSize, uint64_t firstLine)
      : path_(path),
        buffer_(new unsigned char[kBufferBytes]),
        offset_(start),
        size_(fileSize),
        line_(firstLine) {
    file_ = std::fopen(path.c_str(), "rb");
    if (!file_ || ::fseeko(file_, static_cast<off_t>(start), SEEK_SET) != 0)
      throw GlintError("cannot read mesh " + path + ": " + std::strerror(errno));
    at_ = end_ = buffer_.get();
  }
  ~Body() {
    if (file_) std::fclose(file_);
  }
  Body(const Body&) = delete;
  Body& operator=(const Body&) = delete;

  // The file offset of the next byte.
  uint64_t offset() const { return offset_ + uint64_t(at_ - buffer_.get()); }
  // Bytes after the cursor, by the size the file had when it was checked.
  uint64_t left() const { return size_ > offset() ? size_ - offset() : 0; }
  // The file's line the cursor is on (ASCII).
  uint64_t line() const { return line_; }

  // The next `n` bytes (at most a value's 8), or nullptr where the file ends first.
  const unsigned char* bytes(size_t n) {
    if (size_t(end_ - at_) < n) {
      refill(n);
      if (size_t(end_ - at_) < n) return nullptr;
    }
    const unsigned char* p = at_;
    at_ += n;
    return p;
  }

  // Skips `n` bytes; false where the file ends first.
  bool skip(uint64_t n) {
    while (n > 0) {
      if (at_ == end_) {
        refill(1);
        if (at_ == end_) return false;
      }
      const size_t step = size_t(std::min<uint64_t>(n, uint64_t(end_ - at_)));
      at_ += step;
      n -= step;
    }
    return true;
  }

  // Skips blanks to the end of the cursor's line, and past it; false where a token comes first.
  bool endLine() {
    for (;;) {
      while (at_ < end_ && isSpace(*at_) && !endsLine(*at_)) pass(*at_++);
      if (at_ < end_) break;
      refill(1);
      if (at_ == end_) return true;  // the file ends with the line
    }
    if (!endsLine(*at_)) return false;
    pass(*at_++);  // a CR's LF, if it has one, is passed over by the next token
    return true;
  }

  // The next whitespace-separated token; empty at the end of the file. A token is cut at
  // kMaxTokenChars + 1 characters (the caller refuses it).
  std::string_view token() {
    for (;;) {
      while (at_ < end_ && isSpace(*at_)) pass(*at_++);
      if (at_ < end_) break;
      refill(1);
      if (at_ == end_) return {};
    }
    unsigned char* p = at_;
    for (;;) {
      while (p < end_ && !isSpace(*p) && size_t(p - at_) <= kMaxTokenChars) ++p;
      if (p < end_ || size_t(p - at_) > kMaxTokenChars || eof_) break;
      const size_t have = size_t(p - at_);
      refill(have + 1);
      p = at_ + have;
    }
    const std::string_view t(reinterpret_cast<const char*>(at_), size_t(p - at_));
    at_ = p;
    afterCr_ = false;
    return t;
  }

 private:
  static bool isSpace(unsigned char c) {
    return c == ' ' || c == '\n' || c == '\r' || c == '\t' || c == '\v' || c == '\f';
  }
  static bool endsLine(unsigned char c) { return c == '\n' || c == '\r'; }
  // Counts lines as the header does: LF, CR LF and a lone CR each end one.
  void pass(unsigned char c) {
    if (c == '\r' || (c == '\n' && !afterCr_)) ++line_;
    afterCr_ = c == '\r';
  }

  // Keeps the unread bytes and reads until at least `need` are there or the file ends.
  void refill(size_t need) {
    const size_t kept = size_t(end_ - at_);
    offset_ += uint64_t(at_ - buffer_.get());
    std::memmove(buffer_.get(), at_, kept);
    at_ = buffer_.get();
    end_ = at_ + kept;
    while (!eof_ && size_t(end_ - at_) < need) {
      const size_t got = std::fread(end_, 1, kBufferBytes - size_t(end_ - buffer_.get()), file_);
      if (got == 0) {
        if (std::ferror(file_))
          throw GlintError("cannot read mesh " + path_ + ": " + std::strerror(errno));
        eof_ = true;
      }
      end_ += got;
    }
  }

  std::string path_;
  std::FILE* file_ = nullptr;
  std::unique_ptr<unsigned char[]> buffer_;
  unsigned char *at_ = nullptr, *end_ = nullptr;
  uint64_t offset_;  // of buffer_[0] in the file
  uint64_t size_;
  uint64_t line_;
  bool afterCr_ = false;  // the last byte passed was a CR
  bool eof_ = false;
};

inline bool isWhole(PlyType t) { return t != PlyType::Float32 && t != PlyType::Float64; }

inline const char* typeName(PlyType t) {
  static const char* const kNames[] = {"char", "uchar", "short", "ushort",
                                       "int",  "uint",  "float", "double"};
  return kNames[static_cast<int>(t)];
}

inline bool fitsType(int64_t v, PlyType t) {
  switch (t) {
    case PlyType::Int8:
      return v >= -128 && v <= 127;
    case PlyType::UInt8:
      return v >= 0 && v <= 255;
    case PlyType::Int16:
      return v >= -32768 && v <= 32767;
    case PlyType::UInt16:
      return v >= 0 && v <= 65535;
    case PlyType::Int32:
      return v >= INT32_MIN && v <= INT32_MAX;
    case PlyType::UInt32:
      return v >= 0 && v <= int64_t{UINT32_MAX};
    default:
      return true;
  }
}

template <class T>
T load(const unsigned char* p, bool swap) {
  unsigned char b[sizeof(T)];
  std::memcpy(b, p, sizeof b);
  if (swap)
    for (size_t i = 0; i < sizeof b / 2; ++i) std::swap(b[i], b[sizeof b - 1 - i]);
  T v;
  std::memcpy(&v, b, sizeof v);
  return v;
}

// Values of a binary body: every value converts to double exactly (32-bit integers included).
class BinaryValues {
 public:
  BinaryValues(Body& body, bool swap) : body_(body), swap_(swap) {}

  // Binary elements follow one another without separators.
  void beginElement() {}
  void endElement() {}

  double scalar(PlyType t) {
    const unsigned char* p = body_.bytes(size_t(plyTypeSize(t)));
    if (!p) throw Bad{"the file ends inside it"};
    switch (t) {
      case PlyType::Int8:
        return double(int8_t(*p));
      case PlyType::UInt8:
        return double(*p);
      case PlyType::Int16:
        return double(load<int16_t>(p, swap_));
      case PlyType::UInt16:
        return double(load<uint16_t>(p, swap_));
      case PlyType::Int32:
        return double(load<int32_t>(p, swap_));
      case PlyType::UInt32:
        return double(load<uint32_t>(p, swap_));
      case PlyType::Float32:
        return double(load<float>(p, swap_));
      case PlyType::Float64:
        return load<double>(p, swap_);
    }
    return 0;
  }
  int64_t whole(PlyType t) { return int64_t(scalar(t)); }  // t is a whole-number type
  void skipScalar(PlyType t) {
    if (!body_.skip(uint64_t(plyTypeSize(t)))) throw Bad{"the file ends inside it"};
  }
  // A list of `n` values of type `t` must fit in what is left of the file.
  void checkListFits(int64_t n, PlyType t) const {
    const uint64_t needed = uint64_t(n) * uint64_t(plyTypeSize(t));
    if (needed > body_.left())
      throw Bad{"its list of " + std::to_string(n) + " values needs " + std::to_string(needed) +
                " bytes, but the file has " + std::to_string(body_.left()) + " left"};
  }
  void skipList(int64_t n, PlyType t) {
    checkListFits(n, t);
    if (!body_.skip(uint64_t(n) * uint64_t(plyTypeSize(t)))) throw Bad{"the file ends inside it"};
  }
  std::string place() const { return " (byte " + std::to_string(body_.offset()) + ")"; }

 private:
  Body& body_;
  bool swap_;
};

// Values of an ASCII body, one token each.
class AsciiValues {
 public:
  explicit AsciiValues(Body& body) : body_(body) {}

  // Each element on a line of its own, as the format writes them: read as one stream of
  // tokens, a line one value short took the next line's first, and one value long shifted
  // every value after it, both without a word. Blank lines between elements are passed over.
  void beginElement() { started_ = false; }
  void endElement() {
    if (!started_) return;  // an element of no values
    if (!body_.endLine()) throw Bad{"its line holds more values than its properties"};
  }

  double scalar(PlyType t) {
    if (isWhole(t)) return double(whole(t));
    const std::string_view s = next();
    const char* first = s.data() + (s[0] == '+' ? 1 : 0);  // from_chars takes no '+'
    double v = 0;
    const auto [end, ec] = std::from_chars(first, s.data() + s.size(), v);
    if (end != s.data() + s.size() || first == end) throw Bad{quoted(s) + " is not a number"};
    if (ec == std::errc::result_out_of_range) {
      // Past double's range (1e999: infinite, refused as such later) or below it (1e-999: 0).
      const std::string copy(s);
      v = std::strtod(copy.c_str(), nullptr);
    }
    return v;
  }
  int64_t whole(PlyType t) {
    const std::string_view s = next();
    const char* first = s.data() + (s[0] == '+' ? 1 : 0);
    int64_t v = 0;
    const auto [end, ec] = std::from_chars(first, s.data() + s.size(), v);
    if (end != s.data() + s.size() || first == end || ec != std::errc() || !fitsType(v, t))
      throw Bad{quoted(s) + (t == PlyType::Int32 ? " is not an " : " is not a ") + typeName(t)};
    return v;
  }
  void skipScalar(PlyType) { next(); }
  // A list of `n` values needs a separator and a character each.
  void checkListFits(int64_t n, PlyType) const {
    if (uint64_t(n) > body_.left() / 2)
      throw Bad{"its list of " + std::to_string(n) + " values needs at least " +
                std::to_string(2 * uint64_t(n)) + " bytes, but the file has " +
                std::to_string(body_.left()) + " left"};
  }
  void skipList(int64_t n, PlyType t) {
    checkListFits(n, t);
    for (int64_t i = 0; i < n; ++i) next();
  }
  // The element's line once a value of it is read (a short line's fault is its own, not the
  // next line's where its missing value was looked for).
  std::string place() const {
    return " (line " + std::to_string(started_ ? line_ : body_.line()) + ")";
  }

 private:
  std::string_view next() {
    const std::string_view s = body_.token();
    if (s.empty()) throw Bad{"the file ends before it"};
    if (!started_) {
      started_ = true;
      line_ = body_.line();
    } else if (body_.line() != line_) {
      throw Bad{"its line ends before its values do"};
    }
    if (s.size() > kMaxTokenChars)
      throw Bad{"a value is longer than " + std::to_string(kMaxTokenChars) + " characters"};
    return s;
  }
  static std::string quoted(std::string_view s) { return "\"" + excerpt(std::string(s)) + "\""; }

  Body& body_;
  bool started_ = false;  // a value of the element read, on line_
  uint64_t line_ = 0;
};

}  // namespace glint::ply
