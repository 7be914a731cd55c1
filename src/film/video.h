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

struct VideoRequest {
    std::filesystem::path frames;  ///< the folder holding frame-00001.png, frame-00002.png, ...
    int frameCount = 0;
    double fps = 30;
    std::filesystem::path output;  ///< written by ffmpeg (the caller makes it atomic)
    VideoFormat format = VideoFormat::Mp4;
};

/// The name of frame `number` (1-based) in the frames folder.
std::string frameFileName(int number);

/// ffmpeg's command line for `request`: what encodeVideo runs, and the sidecar records.
std::vector<std::string> ffmpegCommand(const VideoRequest& request);

/// Runs ffmpeg; "" on success, else why it failed (ffmpeg missing names the package).
std::string encodeVideo(const VideoRequest& request);

/// `ffmpeg -version`'s first line ("ffmpeg version 5.1.6-0+deb12u1 ..."), or "".
std::string ffmpegVersion();

}  // namespace relief::film
