#pragma once
// Plain-text templates with {{placeholders}} and no logic. Every placeholder
// must be bound and every binding used; either mistake is a diagnostic at the
// template's file:line:col.
#include <cstdio>
#include <functional>
#include <map>
#include <string>

#include "core/diagnostics.h"

namespace relief::emit {

/// A binding is literal text, or a writer that streams a large value
/// (the mesh) straight to the output.
struct Binding {
    std::string text;
    std::function<void(std::FILE*)> writer;  ///< used when set
};
using Bindings = std::map<std::string, Binding>;

struct Template {
    std::string file;  ///< for diagnostics
    std::string text;
};

/// Checks that every placeholder is bound and every binding is used.
bool checkTemplate(const Template& t, const Bindings& bindings, Diagnostics& diags);

/// Writes the template with its placeholders replaced. Precondition: checkTemplate passed.
void renderTemplate(const Template& t, const Bindings& bindings, std::FILE* out);

}  // namespace relief::emit
