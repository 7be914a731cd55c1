#pragma once
// A film's working folder (<film>.film, beside the film) holds a render plan
// a frame and this record, film.json: what the film is made of, so that a run
// that did not finish (interrupted, a POV-Ray or Slurm failure) can be
// finished by another (`relief animate --resume DIR`) without the scene being
// read again. Input: the frames and the film's names. Output: film.json, and
// the record read back and checked (it is untrusted, like any input).
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/diagnostics.h"
#include "film/frames.h"

namespace relief::film {

struct FilmFrame {
    FrameSettings settings;
    bool night = false;  ///< the sun below the horizon: left out (animation.skip_night)
    double sunAltitudeDeg = 0;
    int fileNumber = 0;  ///< its number among the frames kept (the film's and --frames' names); 0 when left out
};

/// The folder of frame `number`'s render plan in the film's working folder.
std::string framePlanName(int number);

struct FilmRecord {
    std::filesystem::path scene;       ///< the scene file, as given
    std::string sceneSha1;
    double fps = 30;
    /// The film and its sidecar (absolute). film.json holds the film's file
    /// name only: read back, both are beside the working folder.
    std::filesystem::path film;
    std::filesystem::path sidecar;
    /// --frames (absolute); empty: none. film.json names no folder outside its
    /// own: it says only whether the frames were kept, and --resume is given
    /// the folder again.
    std::filesystem::path framesDir;
    bool framesKept = false;
    bool filmGiven = false;            ///< -o named the film (its role in messages)
    int terrains = 0;                  ///< terrains compiled
    double compileSeconds = 0;
    std::vector<FilmFrame> frames;     ///< every frame, kept or left out, in film order
    /// The scene's limits.max_film_s and limits.max_memory_mb, and where it set
    /// them: what --resume holds the frames still to render to (its other
    /// limits were the compile's, done).
    scene::LimitsSpec limits;
};

/// Writes `record` as `dir`/film.json (atomically).
void writeFilmRecord(const FilmRecord& record, const std::filesystem::path& dir);

/// The record in `dir`, or nullopt with an error naming film.json and what is
/// wrong (missing, not a film's, damaged, frames out of order, limits out of
/// the scene's ranges, a film's name that is not the folder's).
std::optional<FilmRecord> readFilmRecord(const std::filesystem::path& dir, Diagnostics& diags);

}  // namespace relief::film
