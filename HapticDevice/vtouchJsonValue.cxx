#include "vtouchJsonValue.h"

#include <cstdlib>
#include <cstring>

namespace vtouch
{

/// Recursive-descent parser over the text (RFC 8259 subset: no surrogate pairs beyond the BMP
/// are combined, which preset files never need).
class JsonParser
{
public:
  explicit JsonParser(const std::string& text)
    : Text(text)
  {
  }

  bool document(JsonValue& value, std::string& error)
  {
    if (!this->value(value, 0))
    {
      error = std::string(this->Error) + " at byte " + std::to_string(this->Pos);
      return false;
    }
    this->skipSpace();
    if (this->Pos != this->Text.size())
    {
      error = "trailing characters at byte " + std::to_string(this->Pos);
      return false;
    }
    return true;
  }

private:
  bool fail(const char* message)
  {
    this->Error = message;
    return false;
  }

  void skipSpace()
  {
    while (this->Pos < this->Text.size() &&
           std::strchr(" \t\r\n", this->Text[this->Pos]) != nullptr &&
           this->Text[this->Pos] != '\0')
    {
      ++this->Pos;
    }
  }

  bool literal(const char* word)
  {
    const std::size_t n = std::strlen(word);
    if (this->Text.compare(this->Pos, n, word) != 0)
    {
      return this->fail("invalid literal");
    }
    this->Pos += n;
    return true;
  }

  bool value(JsonValue& v, int depth)
  {
    if (depth > 64)
    {
      return this->fail("nested too deep");
    }
    this->skipSpace();
    if (this->Pos >= this->Text.size())
    {
      return this->fail("unexpected end");
    }
    const char c = this->Text[this->Pos];
    if (c == '{')
    {
      return this->object(v, depth);
    }
    if (c == '[')
    {
      return this->array(v, depth);
    }
    if (c == '"')
    {
      v.Kind = JsonValue::Type::String;
      return this->string(v.Text);
    }
    if (c == 't' || c == 'f')
    {
      v.Kind = JsonValue::Type::Boolean;
      v.Bool = c == 't';
      return this->literal(c == 't' ? "true" : "false");
    }
    if (c == 'n')
    {
      v.Kind = JsonValue::Type::Null;
      return this->literal("null");
    }
    return this->number(v);
  }

  bool number(JsonValue& v)
  {
    const std::size_t start = this->Pos;
    if (this->Pos < this->Text.size() && this->Text[this->Pos] == '-')
    {
      ++this->Pos;
    }
    const std::size_t digits = this->Pos;
    while (this->Pos < this->Text.size() &&
           std::strchr("0123456789.eE+-", this->Text[this->Pos]) != nullptr &&
           this->Text[this->Pos] != '\0')
    {
      ++this->Pos;
    }
    if (this->Pos == digits)
    {
      return this->fail("unexpected character");
    }
    const std::string token = this->Text.substr(start, this->Pos - start);
    char* end = nullptr;
    v.Number = std::strtod(token.c_str(), &end);
    if (end != token.c_str() + token.size())
    {
      return this->fail("invalid number");
    }
    v.Kind = JsonValue::Type::Number;
    return true;
  }

  bool string(std::string& out)
  {
    ++this->Pos; // opening quote
    out.clear();
    while (this->Pos < this->Text.size())
    {
      const char c = this->Text[this->Pos++];
      if (c == '"')
      {
        return true;
      }
      if (static_cast<unsigned char>(c) < 0x20)
      {
        return this->fail("control character in string");
      }
      if (c != '\\')
      {
        out.push_back(c);
        continue;
      }
      if (this->Pos >= this->Text.size())
      {
        break;
      }
      const char e = this->Text[this->Pos++];
      switch (e)
      {
        case '"':
          out.push_back('"');
          break;
        case '\\':
          out.push_back('\\');
          break;
        case '/':
          out.push_back('/');
          break;
        case 'b':
          out.push_back('\b');
          break;
        case 'f':
          out.push_back('\f');
          break;
        case 'n':
          out.push_back('\n');
          break;
        case 'r':
          out.push_back('\r');
          break;
        case 't':
          out.push_back('\t');
          break;
        case 'u':
        {
          if (this->Pos + 4 > this->Text.size())
          {
            return this->fail("truncated \\u escape");
          }
          unsigned code = 0;
          for (int i = 0; i < 4; ++i)
          {
            const char h = this->Text[this->Pos++];
            code <<= 4;
            if (h >= '0' && h <= '9')
              code |= static_cast<unsigned>(h - '0');
            else if (h >= 'a' && h <= 'f')
              code |= static_cast<unsigned>(h - 'a' + 10);
            else if (h >= 'A' && h <= 'F')
              code |= static_cast<unsigned>(h - 'A' + 10);
            else
              return this->fail("invalid \\u escape");
          }
          // UTF-8 encode the code point (BMP).
          if (code < 0x80)
          {
            out.push_back(static_cast<char>(code));
          }
          else if (code < 0x800)
          {
            out.push_back(static_cast<char>(0xC0 | (code >> 6)));
            out.push_back(static_cast<char>(0x80 | (code & 0x3F)));
          }
          else
          {
            out.push_back(static_cast<char>(0xE0 | (code >> 12)));
            out.push_back(static_cast<char>(0x80 | ((code >> 6) & 0x3F)));
            out.push_back(static_cast<char>(0x80 | (code & 0x3F)));
          }
          break;
        }
        default:
          return this->fail("invalid escape");
      }
    }
    return this->fail("unterminated string");
  }

  bool array(JsonValue& v, int depth)
  {
    ++this->Pos;
    v.Kind = JsonValue::Type::Array;
    this->skipSpace();
    if (this->Pos < this->Text.size() && this->Text[this->Pos] == ']')
    {
      ++this->Pos;
      return true;
    }
    while (true)
    {
      v.Items.emplace_back();
      if (!this->value(v.Items.back(), depth + 1))
      {
        return false;
      }
      this->skipSpace();
      if (this->Pos >= this->Text.size())
      {
        return this->fail("unterminated array");
      }
      const char c = this->Text[this->Pos++];
      if (c == ']')
      {
        return true;
      }
      if (c != ',')
      {
        return this->fail("expected ',' or ']'");
      }
    }
  }

  bool object(JsonValue& v, int depth)
  {
    ++this->Pos;
    v.Kind = JsonValue::Type::Object;
    this->skipSpace();
    if (this->Pos < this->Text.size() && this->Text[this->Pos] == '}')
    {
      ++this->Pos;
      return true;
    }
    while (true)
    {
      this->skipSpace();
      if (this->Pos >= this->Text.size() || this->Text[this->Pos] != '"')
      {
        return this->fail("expected a key");
      }
      std::string key;
      if (!this->string(key))
      {
        return false;
      }
      this->skipSpace();
      if (this->Pos >= this->Text.size() || this->Text[this->Pos] != ':')
      {
        return this->fail("expected ':'");
      }
      ++this->Pos;
      JsonValue member;
      if (!this->value(member, depth + 1))
      {
        return false;
      }
      v.Members[key] = std::move(member);
      this->skipSpace();
      if (this->Pos >= this->Text.size())
      {
        return this->fail("unterminated object");
      }
      const char c = this->Text[this->Pos++];
      if (c == '}')
      {
        return true;
      }
      if (c != ',')
      {
        return this->fail("expected ',' or '}'");
      }
    }
  }

  const std::string& Text;
  std::size_t Pos = 0;
  const char* Error = "";
};

bool JsonValue::parse(const std::string& text, JsonValue& value, std::string& error)
{
  JsonValue result;
  JsonParser parser(text);
  if (!parser.document(result, error))
  {
    return false;
  }
  value = std::move(result);
  return true;
}

const JsonValue* JsonValue::find(const std::string& key) const
{
  if (this->Kind != Type::Object)
  {
    return nullptr;
  }
  const auto it = this->Members.find(key);
  return it == this->Members.end() ? nullptr : &it->second;
}

double JsonValue::numberAt(const std::string& key, double fallback) const
{
  const JsonValue* v = this->find(key);
  return v ? v->number(fallback) : fallback;
}

bool JsonValue::booleanAt(const std::string& key, bool fallback) const
{
  const JsonValue* v = this->find(key);
  return v ? v->boolean(fallback) : fallback;
}

std::string JsonValue::stringAt(const std::string& key, const std::string& fallback) const
{
  const JsonValue* v = this->find(key);
  return v ? v->string(fallback) : fallback;
}

} // namespace vtouch
