// What the OpenAL adapter costs a game per frame (bench/RESULTS.md): N AL
// sources playing looping buffers on OpenAL Soft's null output, each frame
// one Adapter::update() timed (the AL reads and the queued SoundScene
// changes), then one simulation step, untimed, that takes the queue.
//   bench_openal [--sources 32,256] [--frames 600] [--warmup 60]
#include <AL/al.h>
#include <AL/alc.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include "soundpaint/openal.h"

namespace {

struct Options {
  std::vector<int> sources = {32, 256};
  int frames = 600;
  int warmup = 60;
};

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string key = argv[i], value = argv[i + 1];
    if (key == "--sources") {
      o.sources.clear();
      std::stringstream list(value);
      for (std::string item; std::getline(list, item, ',');) o.sources.push_back(std::stoi(item));
    } else if (key == "--frames") {
      o.frames = std::stoi(value);
    } else if (key == "--warmup") {
      o.warmup = std::stoi(value);
    } else {
      std::fprintf(stderr, "bench_openal: unknown option %s (--sources, --frames, --warmup)\n", key.c_str());
      std::exit(2);
    }
  }
  return o;
}

// A flat floor 100 m square: every source's rays have somewhere to land.
sp::Scene floor_scene() {
  sp::Scene scene;
  scene.layer_names = {"concrete"};
  const float h = 50.0f;
  const float quad[] = {-h, 0, -h, -h, 0, h, h, 0, h, -h, 0, -h, h, 0, h, h, 0, -h};
  for (int v = 0; v < 6; ++v) scene.vertices.push_back(sp::Vec3(quad[3 * v], quad[3 * v + 1], quad[3 * v + 2]));
  scene.triangle_layers = {0, 0};
  return scene;
}

}  // namespace

int main(int argc, char** argv) {
  const Options options = parse(argc, argv);
  setenv("ALSOFT_DRIVERS", "null", 0);
  ALCdevice* device = alcOpenDevice(nullptr);
  const ALCint attributes[] = {ALC_MONO_SOURCES, 1024, 0};
  ALCcontext* context = device != nullptr ? alcCreateContext(device, attributes) : nullptr;
  if (context == nullptr || alcMakeContextCurrent(context) != ALC_TRUE) {
    std::fprintf(stderr, "bench_openal: no OpenAL device (even the null one)\n");
    return 1;
  }
  std::printf("OpenAL: %s %s, device %s\n", alGetString(AL_RENDERER), alGetString(AL_VERSION),
              alcGetString(device, ALC_DEVICE_SPECIFIER));
  std::vector<ALshort> pcm(22050);
  for (std::size_t i = 0; i < pcm.size(); ++i) pcm[i] = static_cast<ALshort>(i % 2 == 0 ? 8000 : -8000);
  std::printf("%8s %12s %12s %12s\n", "sources", "median_us", "p99_us", "us/source");
  for (int n : options.sources) {
    sp::Config config;
    config.ray_budget = 0;  // the adapter alone: no rays
    config.listener_position = sp::Vec3(0, 1, 0);
    auto sim = sp::create_cpu_simulator(sp::make_world(floor_scene(), config).value(), sp::CpuSettings{1}).value();
    sp::openal::Adapter adapter(sim->scene());
    ALuint buffer = 0;
    alGenBuffers(1, &buffer);
    if (!adapter.buffer_data(buffer, AL_FORMAT_MONO16, pcm.data(), ALsizei(pcm.size() * 2), 22050, "bench").ok())
      return 1;
    std::vector<ALuint> sources(static_cast<std::size_t>(n));
    alGenSources(n, sources.data());
    if (alGetError() != AL_NO_ERROR) {
      std::fprintf(stderr, "bench_openal: cannot make %d AL sources\n", n);
      return 1;
    }
    for (int k = 0; k < n; ++k) {
      const ALuint source = sources[static_cast<std::size_t>(k)];
      alSourcei(source, AL_BUFFER, static_cast<ALint>(buffer));
      alSourcei(source, AL_LOOPING, AL_TRUE);
      alSource3f(source, AL_POSITION, float(k % 16) - 8.0f, 1.0f, float(k / 16) - 8.0f);
      alSourcePlay(source);
    }
    std::vector<double> us;
    for (int frame = 0; frame < options.warmup + options.frames; ++frame) {
      for (int k = 0; k < n; k += 8)
        alSource3f(sources[static_cast<std::size_t>(k)], AL_POSITION, float(frame % 7), 1.0f, float(k % 5));
      const auto start = std::chrono::steady_clock::now();
      auto report = adapter.update();
      const auto end = std::chrono::steady_clock::now();
      if (!report.ok() || report.value().playing != static_cast<std::uint32_t>(n)) {
        std::fprintf(stderr, "bench_openal: update saw %u of %d playing: %s\n",
                     report.ok() ? report.value().playing : 0, n, report.ok() ? "" : report.error().message.c_str());
        return 1;
      }
      if (!sim->step().ok()) return 1;
      if (frame >= options.warmup) us.push_back(std::chrono::duration<double, std::micro>(end - start).count());
    }
    std::sort(us.begin(), us.end());
    const double median = us[us.size() / 2], p99 = us[std::min(us.size() - 1, us.size() * 99 / 100)];
    std::printf("%8d %12.1f %12.1f %12.2f\n", n, median, p99, median / n);
    alDeleteSources(n, sources.data());
    alDeleteBuffers(1, &buffer);
  }
  alcMakeContextCurrent(nullptr);
  alcDestroyContext(context);
  alcCloseDevice(device);
  return 0;
}
