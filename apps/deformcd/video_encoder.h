#pragma once
// Encoding numbered PNG frames into a video with an ffmpeg found on PATH (never bundled).

#include <filesystem>

namespace deformcd::app {

// Runs `ffmpeg` on DIR/frame_00000.png, frame_00001.png... (`first_frame` on, consecutive) at
// `fps` frames per second, writing `video` atomically (a temporary next to it, renamed when
// ffmpeg succeeds). Throws Error naming the video and ffmpeg's exit status on failure.
void encode_video(const std::filesystem::path& ffmpeg, const std::filesystem::path& frames_dir,
                  int first_frame, double fps, const std::filesystem::path& video);

}  // namespace deformcd::app
