#pragma once
// A film's frames encoded by Debian's ffmpeg. Input: numbered PNGs in a
// folder. Output: an H.264 MP4 (yuv420p, even sizes, the index at the front
// so that a browser plays it as it downloads), a VP9 WebM or an animated GIF,
// told by the output's extension. The same frames give the same bytes: the
// encoders' bit-exact flags, a fixed thread count, no dates or versions in
// the file.
#include <filesystem>
#include <string>
#include <vector>

namespace relief::film {

enum class VideoFormat { Mp4, WebM, Gif };

/// The format an output's extension names (.mp4, .webm, .gif, any case);
/// false for any other.
bool videoFormatOf(const std::filesystem::path& output, VideoFormat& format);

/// ffmpeg runs in the film's working folder and sees fixed names only: it
/// reads frames/frame-00001.png, ... (a pattern: a % in a user's folder name
/// would be taken for one) and writes film.mp4 (.webm, .gif) there, which is
/// then moved to `output`. So the film's bytes are the same whatever the film,
/// its folder or the frames' folder are called (the MP4 muxer's bytes depend
/// on the length of the names it is given).
struct VideoRequest {
    std::filesystem::path workDir;  ///< holds frames/ with frame-00001.png, frame-00002.png, ...
    int frameCount = 0;
    double fps = 30;
    std::filesystem::path output;  ///< where the film goes (the caller makes it atomic)
    VideoFormat format = VideoFormat::Mp4;
};

/// The name of frame `number` (1-based) in the frames folder.
std::string frameFileName(int number);

/// ffmpeg's command line for `request`, run in its working folder: what
/// encodeVideo runs, and the sidecar records.
std::vector<std::string> ffmpegCommand(const VideoRequest& request);

/// Runs ffmpeg; "" on success, else why it failed (ffmpeg missing names the package).
std::string encodeVideo(const VideoRequest& request);

/// `ffmpeg -version`'s first line ("ffmpeg version 5.1.6-0+deb12u1 ..."), or "".
std::string ffmpegVersion();

}  // namespace relief::film
