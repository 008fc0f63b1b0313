// Small text helpers for reading file names and volume headers. Internal to VesselTouchIO.
#ifndef vtouchHeaderText_h
#define vtouchHeaderText_h

#include <algorithm>
#include <cctype>
#include <string>

namespace vtouch
{

/// `text` in lower case (ASCII).
inline std::string lowerCase(std::string text)
{
  std::transform(text.begin(),
    text.end(),
    text.begin(),
    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

inline bool endsWith(const std::string& text, const std::string& suffix)
{
  return text.size() >= suffix.size() &&
         text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

/// `text` without leading and trailing blanks and line ends.
inline std::string trimmed(const std::string& text)
{
  const auto begin = text.find_first_not_of(" \t\r\n");
  if (begin == std::string::npos)
  {
    return std::string();
  }
  const auto end = text.find_last_not_of(" \t\r\n");
  return text.substr(begin, end - begin + 1);
}

} // namespace vtouch

#endif
