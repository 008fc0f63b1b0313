// A small JSON reader for device presets (C++17 only: this library takes no JSON dependency).
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <vector>

namespace vtouch
{

/// A parsed JSON value. Objects keep their members sorted by key (presets are small).
class JsonValue
{
public:
  enum class Type
  {
    Null,
    Boolean,
    Number,
    String,
    Array,
    Object
  };

  /// Parses a whole document. Returns false with `error` (and its byte offset) on bad input.
  /// Nesting is limited to 64 levels.
  static bool parse(const std::string& text, JsonValue& value, std::string& error);

  Type type() const { return this->Kind; }
  bool isNull() const { return this->Kind == Type::Null; }
  bool isObject() const { return this->Kind == Type::Object; }
  bool isArray() const { return this->Kind == Type::Array; }

  /// Member lookup; null when absent or when this is not an object.
  const JsonValue* find(const std::string& key) const;
  /// Array elements (empty when not an array).
  const std::vector<JsonValue>& items() const { return this->Items; }
  const std::map<std::string, JsonValue>& members() const { return this->Members; }

  /// Typed reads with a fallback when the value is absent or of another type.
  double number(double fallback) const
  {
    return this->Kind == Type::Number ? this->Number : fallback;
  }
  bool boolean(bool fallback) const { return this->Kind == Type::Boolean ? this->Bool : fallback; }
  std::string string(const std::string& fallback) const
  {
    return this->Kind == Type::String ? this->Text : fallback;
  }

  /// Shorthands for members: `numberAt("maxForce_N", 1.0)`.
  double numberAt(const std::string& key, double fallback) const;
  bool booleanAt(const std::string& key, bool fallback) const;
  std::string stringAt(const std::string& key, const std::string& fallback) const;

private:
  friend class JsonParser;
  Type Kind = Type::Null;
  bool Bool = false;
  double Number = 0.0;
  std::string Text;
  std::vector<JsonValue> Items;
  std::map<std::string, JsonValue> Members;
};

} // namespace vtouch
