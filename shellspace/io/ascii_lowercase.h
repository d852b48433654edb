// Lower-casing the words the readers and the option parsers accept case-
// insensitively (file extensions, shading, colour and view names).
#ifndef SHELLSPACE_IO_ASCII_LOWERCASE_H_
#define SHELLSPACE_IO_ASCII_LOWERCASE_H_

#include <cctype>
#include <string>

namespace shellspace {

// `text` with every ASCII letter A-Z replaced by its lower case; other bytes
// (UTF-8 included) are kept.
inline std::string AsciiLowercase(std::string text) {
  for (char& c : text) {
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  return text;
}

}  // namespace shellspace

#endif  // SHELLSPACE_IO_ASCII_LOWERCASE_H_
