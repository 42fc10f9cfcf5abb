#pragma once
// JSON scene text (comments allowed) parsed by nlohmann-json, plus a map from every value's JSON
// pointer to its line, so each error can name file:line and the path (`objects[3].radius`).
#include <nlohmann/json.hpp>

#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "core/affine.h"
#include "core/error.h"
#include "core/rgb.h"
#include "core/vec.h"

namespace glint {

class JsonDocument {
 public:
  // Throws SceneError with the line of a syntax error.
  JsonDocument(const std::string& text, std::string fileName);

  const nlohmann::json& root() const { return root_; }
  const std::string& fileName() const { return fileName_; }
  // Line of the value (or of its key, inside objects) at `pointer`; 0 if unknown.
  int lineOf(const std::string& pointer) const;

 private:
  std::string fileName_;
  nlohmann::json root_;
  std::unordered_map<uint64_t, int> lines_;  // by a hash of the JSON pointer (json_source.cpp)
};

// A located view of one JSON value with typed, validated accessors. Every failure throws
// SceneError naming file, line, path and the problem.
class JsonNode {
 public:
  JsonNode(const JsonDocument& doc, const nlohmann::json& value, std::string pointer,
           std::string path)
      : doc_(&doc), value_(&value), pointer_(std::move(pointer)), path_(std::move(path)) {}

  [[noreturn]] void fail(const std::string& problem) const;
  const std::string& path() const { return path_; }
  const nlohmann::json& raw() const { return *value_; }
  FileLoc loc() const { return {doc_->fileName(), doc_->lineOf(pointer_)}; }

  bool isObject() const { return value_->is_object(); }
  bool isArray() const { return value_->is_array(); }
  bool isString() const { return value_->is_string(); }
  bool isNumber() const { return value_->is_number(); }

  // Object access. checkKeys rejects keys outside `allowed`, suggesting the nearest one.
  void checkKeys(std::initializer_list<std::string_view> allowed) const;
  void checkKeys(const std::vector<std::string>& allowed) const;
  bool has(const std::string& key) const;
  JsonNode at(const std::string& key) const;  // required
  std::optional<JsonNode> get(const std::string& key) const;
  std::vector<std::string> keys() const;

  // Array access.
  size_t size() const;
  JsonNode operator[](size_t i) const;
  std::vector<JsonNode> elements() const;

  double real() const;   // finite and within float range
  float number() const;  // finite
  float number(float lo, float hi, bool loOpen = false) const;
  int integer(int lo, int hi) const;
  uint64_t unsignedInteger() const;
  bool boolean() const;
  std::string string() const;
  std::string choice(std::initializer_list<std::string_view> options) const;
  Vec3f vec3() const;
  Vec3d vec3d() const;      // for positions: placed in double, rounded once (io/placement.h)
  Vec3f direction() const;  // non-zero, normalised
  Rgb color() const;        // every channel ≥ 0

  // Optional-key helpers: the default when the key is absent.
  Vec3f vec3(const std::string& key, Vec3f dflt) const;
  Rgb color(const std::string& key, Rgb dflt) const;

 private:
  JsonNode child(const nlohmann::json& value, const std::string& key) const;
  std::string typeName() const;

  const JsonDocument* doc_;
  const nlohmann::json* value_;
  std::string pointer_, path_;
};

// Nearest candidate within a small edit distance, for "did you mean" hints; empty if none.
// A number as error messages show it: the shortest of %.9g (a float read back exactly).
std::string formatNumber(double v);

std::string nearestName(const std::string& name, const std::vector<std::string>& candidates);

}  // namespace glint
