#include "film/video.h"

#include <fmt/format.h>

#include "core/number_format.h"
#include "core/text_escape.h"
#include "execute/command.h"
#include "render/povray.h"

namespace relief::film {

bool videoFormatOf(const std::filesystem::path& output, VideoFormat& format) {
    const std::string ext = asciiLower(output.extension().string());
    if (ext == ".mp4")
        format = VideoFormat::Mp4;
    else if (ext == ".webm")
        format = VideoFormat::WebM;
    else if (ext == ".gif")
        format = VideoFormat::Gif;
    else
        return false;
    return true;
}

std::string frameFileName(int number) {
    return fmt::format("frame-{:05}.png", number);
}

namespace {

const char* kFramesPattern = "frames/frame-%05d.png";

// The film ffmpeg writes in the working folder.
std::string encodedName(VideoFormat format) {
    switch (format) {
        case VideoFormat::WebM: return "film.webm";
        case VideoFormat::Gif: return "film.gif";
        default: return "film.mp4";
    }
}

}  // namespace

std::vector<std::string> ffmpegCommand(const VideoRequest& r) {
    // Even sizes for 4:2:0 (a pixel cropped, not a black line added); the
    // colour conversion bit-exact, so that every CPU gives the same bytes.
    const std::string even = "crop=trunc(iw/2)*2:trunc(ih/2)*2";
    const std::string toYuv = "scale=flags=bitexact+accurate_rnd+full_chroma_int:out_color_matrix=bt709,format=yuv420p";
    std::vector<std::string> argv = {"ffmpeg",
                                     "-nostdin",
                                     "-hide_banner",
                                     "-loglevel",
                                     "error",
                                     "-y",
                                     "-framerate",
                                     formatShortest(r.fps),
                                     "-start_number",
                                     "1",
                                     "-i",
                                     kFramesPattern,
                                     "-frames:v",
                                     std::to_string(r.frameCount)};
    const auto add = [&](std::initializer_list<std::string> more) { argv.insert(argv.end(), more); };
    switch (r.format) {
        case VideoFormat::Mp4:
            // x264's output depends on its thread count, never on the machine's: fix it.
            add({"-vf",
                 even + "," + toYuv,
                 "-c:v",
                 "libx264",
                 "-preset",
                 "medium",
                 "-crf",
                 "18",
                 "-threads",
                 "4",
                 "-color_primaries",
                 "bt709",
                 "-color_trc",
                 "bt709",
                 "-colorspace",
                 "bt709",
                 "-movflags",
                 "+faststart",
                 "-f",
                 "mp4"});
            break;
        case VideoFormat::WebM:
            add({"-vf",
                 even + "," + toYuv,
                 "-c:v",
                 "libvpx-vp9",
                 "-b:v",
                 "0",
                 "-crf",
                 "31",
                 "-row-mt",
                 "0",
                 "-threads",
                 "1",
                 "-color_primaries",
                 "bt709",
                 "-color_trc",
                 "bt709",
                 "-colorspace",
                 "bt709",
                 "-f",
                 "webm"});
            break;
        case VideoFormat::Gif:
            // One palette for the whole film, made from its frames (no dither noise between frames).
            add({"-vf", "split[a][b];[a]palettegen=stats_mode=full[p];[b][p]paletteuse=dither=bayer:bayer_scale=3",
                 "-loop", "0", "-f", "gif"});
            break;
    }
    add({"-map_metadata", "-1", "-fflags", "+bitexact", "-flags:v", "+bitexact", encodedName(r.format)});
    return argv;
}

std::string encodeVideo(const VideoRequest& r) {
    if (render::findOnPath("ffmpeg").empty())
        return "ffmpeg is not installed, and it encodes the film (Debian: apt-get install ffmpeg)";
    const std::filesystem::path encoded = r.workDir / encodedName(r.format);
    std::error_code ec;
    std::filesystem::remove(encoded, ec);  // a run interrupted while encoding left it
    const execute::CommandOutput out = execute::runCommand(ffmpegCommand(r), {r.workDir, 0});
    if (out.status != 0)
        return fmt::format("ffmpeg failed{}: {}", out.status > 0 ? fmt::format(" (exit {})", out.status) : "",
                           terminalText(execute::firstLine(out.output), 300));
    std::filesystem::rename(encoded, r.output, ec);
    if (ec) std::filesystem::copy_file(encoded, r.output, std::filesystem::copy_options::overwrite_existing, ec);
    return ec ? fmt::format("the film cannot be written: {}", ec.message()) : "";
}

std::string ffmpegVersion() {
    if (render::findOnPath("ffmpeg").empty()) return "";
    const execute::CommandOutput out = execute::runCommand({"ffmpeg", "-version"});
    return out.status == 0 ? execute::firstLine(out.output) : "";
}

}  // namespace relief::film
