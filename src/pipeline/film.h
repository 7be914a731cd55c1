#pragma once
// relief animate: a film. Each frame is the scene with its own keys set
// (film/frames.h); frames that differ only in the view share one compiled
// terrain (compileSharedTerrain), each frame a render plan of its own whose
// tiles go through the plan's executors (here or on Slurm); the frames are
// finished as stills are, then encoded by ffmpeg (film/video.h). The film,
// its sidecar and the frames asked for are one output set: all or nothing.
#include <filesystem>
#include <vector>

#include "film/film_record.h"
#include "film/frames.h"
#include "film/video.h"
#include "pipeline/job.h"

namespace relief {

struct AnimateJob {
    std::filesystem::path scenePath;
    scene::SceneOverrides overrides;
    std::filesystem::path output;     ///< the film (.mp4, .webm, .gif); "" = out/<scene name>.mp4
    std::filesystem::path framesDir;  ///< also each frame's PNG there (frame-00001.png, ...); "" = none
    std::filesystem::path templatesDir;
    int threads = 0;      ///< refiner threads; 0 = all cores
    int tiles = 1;        ///< strips of each frame
    execute::Options execution;  ///< where the tiles render, and whether POV-Ray is sandboxed
};

using film::FilmFrame;

struct AnimateOutcome {
    JobStatus status = JobStatus::BadInput;
    std::filesystem::path film, sidecar;
    std::vector<FilmFrame> frames;
    int terrains = 0;  ///< terrains compiled: 1 unless a varied key changes the terrain
    double compileSeconds = 0, probeSeconds = 0, renderSeconds = 0, encodeSeconds = 0;
    std::string toolError;  ///< POV-Ray's or ffmpeg's own words (status ToolFailed)
    /// The film's working folder (<film>.film: a plan a frame, film.json),
    /// kept when the film was not made after its frames were planned:
    /// `relief animate --resume` of it renders what is missing.
    std::filesystem::path workDir;
};

/// Loads the scene, compiles and renders every frame, encodes the film and
/// writes it with its sidecar (and --frames) as one set. Errors go to
/// `diags` at the key they belong to; progress to `progress` (may be empty).
AnimateOutcome runAnimateJob(const AnimateJob& job, Diagnostics& diags, const ProgressFn& progress);

/// `relief animate --resume DIR`: a kept working folder's missing tiles
/// rendered (`execution` says where), then the film made as runAnimateJob
/// makes it, from the folder alone (the scene is not read again). Its record
/// names no folder outside it: `framesDir` is where --frames go, which a film
/// whose first run kept its frames must be given again.
AnimateOutcome resumeFilm(const std::filesystem::path& workDir, const execute::Options& execution,
                          const std::filesystem::path& framesDir, Diagnostics& diags, const ProgressFn& progress);

}  // namespace relief
