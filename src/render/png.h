#pragma once
#include <filesystem>
#include <string>

namespace relief::render {

/// Re-encodes a PNG with its pixels only (no date, software or comment
/// chunks), so identical pixels give identical bytes. Writes `out` atomically.
/// Returns "" on success, else the reason.
std::string writeCanonicalPng(const std::filesystem::path& in, const std::filesystem::path& out);

}  // namespace relief::render
