#pragma once
// Every file relief reads is untrusted: it may be a FIFO that never ends, a
// device (/dev/zero), a folder, or far larger than its kind of file can be.
// One reader for all of them: it opens without blocking, refuses what is not
// a regular file, and reads no more than the kind's cap.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

namespace relief {

/// The most bytes a reader takes of each kind of text file (they are all a
/// few kB in use; the caps keep a wrong file from filling memory).
inline constexpr std::uintmax_t kMaxSceneBytes = 4'000'000;
inline constexpr std::uintmax_t kMaxTemplateBytes = 1'000'000;
inline constexpr std::uintmax_t kMaxPaletteBytes = 1'000'000;
inline constexpr std::uintmax_t kMaxManifestBytes = 4'000'000;
inline constexpr std::uintmax_t kMaxCurveBytes = 64'000'000;

/// Why `path` cannot be read as an input file, as the end of a sentence
/// ("it is a FIFO (a named pipe), not a file"), or "" when it is a regular
/// file that can be opened and is at most `maxBytes` long (0: any size).
/// For files another library opens (GDAL, OpenImageIO, libpng): they would
/// block on a FIFO or read a device for ever.
std::string inputFileProblem(const std::filesystem::path& path, std::uintmax_t maxBytes = 0);

/// Why `path` is not a regular file of its own, or "": like
/// inputFileProblem, but a symbolic link is a problem too ("it is a link"),
/// never followed. For the files of relief's own working folders (a render
/// plan's, a film's), where a link can only have been planted.
std::string plainFileProblem(const std::filesystem::path& path);

/// Reads a whole regular file of at most `maxBytes`, without blocking on a
/// FIFO and without following it to a device; nullopt with `problem` set
/// (as inputFileProblem words it) otherwise.
std::optional<std::string> readInputFile(const std::filesystem::path& path, std::uintmax_t maxBytes,
                                         std::string& problem);

/// The first `maxBytes` of a regular file (less when it is shorter), as
/// readInputFile reads whole files: to tell what a file is.
std::optional<std::string> readInputHead(const std::filesystem::path& path, std::uintmax_t maxBytes,
                                         std::string& problem);

/// Whether `path` lies in `folder` or below it, links resolved as far as
/// the path exists (a link out of the folder is outside it).
bool pathInside(const std::filesystem::path& path, const std::filesystem::path& folder);

/// "8.59 GB", "1.5 MB", "12 kB", "300 bytes": a size for a message.
std::string byteSize(std::uintmax_t bytes);

}  // namespace relief
