#include "video_encoder.h"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

#include "deformcd/error.h"

extern char** environ;

namespace deformcd::app {

namespace fs = std::filesystem;

void encode_video(const fs::path& ffmpeg, const fs::path& frames_dir, int first_frame, double fps,
                  const fs::path& video) {
  // ffmpeg picks the container from the extension, so the temporary keeps it.
  const fs::path temporary =
      video.parent_path() / (video.stem().string() + ".partial" + video.extension().string());
  std::ostringstream rate;  // "60", not std::to_string's "60.000000"
  rate << fps;
  std::vector<std::string> args = {
      ffmpeg.string(), "-y", "-loglevel", "error", "-framerate", rate.str(), "-start_number",
      std::to_string(first_frame), "-i", (frames_dir / "frame_%05d.png").string(),
      // Most players want 4:2:0 chroma, which needs even sizes.
      "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-pix_fmt", "yuv420p", temporary.string()};
  std::vector<char*> argv;
  argv.reserve(args.size() + 1);
  for (std::string& arg : args)
    argv.push_back(arg.data());
  argv.push_back(nullptr);

  pid_t pid = 0;
  const int spawn_error = posix_spawn(&pid, argv[0], nullptr, nullptr, argv.data(), environ);
  if (spawn_error != 0) {
    throw Error(video.string() + ": cannot run " + ffmpeg.string() + ": " +
                std::generic_category().message(spawn_error));
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) throw Error(video.string() + ": lost track of ffmpeg (waitpid failed)");
  }
  std::error_code ec;
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    fs::remove(temporary, ec);
    throw Error(video.string() + ": ffmpeg failed (" +
                (WIFEXITED(status) ? "exit status " + std::to_string(WEXITSTATUS(status))
                                   : std::string("killed by a signal")) +
                ") encoding " + (frames_dir / "frame_%05d.png").string());
  }
  fs::rename(temporary, video, ec);
  if (ec) {
    const std::string why = ec.message();
    fs::remove(temporary, ec);
    throw Error(video.string() + ": cannot move the encoded video into place: " + why);
  }
}

}  // namespace deformcd::app
