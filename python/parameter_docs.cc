#include "python/parameter_docs.h"

#include <cstring>

namespace shellspace {
namespace pymodule {
namespace {

struct ParameterDoc {
  const char* function;
  const char* block;  // "Parameters:\n    name: text (default x)\n..."
};

constexpr ParameterDoc kParameterDocs[] = {
#include "python/parameter_docs.inc"
};

}  // namespace

std::string WithParameters(const char* function, const char* text) {
  for (const ParameterDoc& doc : kParameterDocs) {
    if (std::strcmp(doc.function, function) == 0)
      return std::string(text) + "\n\n" + doc.block;
  }
  return text;
}

}  // namespace pymodule
}  // namespace shellspace
