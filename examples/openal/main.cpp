// A program that plays real audio through OpenAL Soft while its player walks
// the bundled level, and gets cues that follow its sounds from two
// soundpaint calls: one beside each alBufferData, one a frame (README.md
// "OpenAL"). The sounds are made at build time by sox and espeak-ng
// (make_sounds.sh): footsteps of someone walking in the first room, an
// alarm behind its east wall, a voice from its far corner after a second.
//
//   soundpaint_openal_example SCENE SOUNDS_DIR OUT_DIR
//
// writes OUT_DIR/openal-frame-060.png, -120 and -180 (1, 2 and 3 s), from
// the player's eyes towards the walker. With ALSOFT_DRIVERS=null (CI) OpenAL
// Soft mixes into nothing; without it, you hear what the pictures show.
// The soundpaint lines are between `>>> soundpaint` and `<<< soundpaint`.
#include <AL/al.h>
#include <AL/alc.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <map>
#include <string>
#include <thread>

#include "picture.h"
#include "wav_file.h"
// >>> soundpaint
#include "soundpaint/openal.h"
// <<< soundpaint

namespace {

sp::Vec3 lerp(sp::Vec3 a, sp::Vec3 b, float s) {
  return {a.x + (b.x - a.x) * s, a.y + (b.y - a.y) * s, a.z + (b.z - a.z) * s};
}

// The game's own AL setup: a device, a context, buffers and sources.
struct Audio {
  ALCdevice* device = nullptr;
  ALCcontext* context = nullptr;
  Audio() {
    device = alcOpenDevice(nullptr);
    if (device == nullptr) throw std::runtime_error("no OpenAL device (set ALSOFT_DRIVERS=null to run without one)");
    context = alcCreateContext(device, nullptr);
    if (context == nullptr || alcMakeContextCurrent(context) != ALC_TRUE)
      throw std::runtime_error("cannot make an OpenAL context current");
  }
  ~Audio() {
    alcMakeContextCurrent(nullptr);
    if (context != nullptr) alcDestroyContext(context);
    alcCloseDevice(device);
  }
};

constexpr int kFrames = 180;  // 3 s at 60 frames a second

}  // namespace

int main(int argc, char** argv) try {
  if (argc != 4) {
    std::fprintf(stderr, "usage: soundpaint_openal_example SCENE SOUNDS_DIR OUT_DIR\n");
    return 2;
  }
  const std::filesystem::path scene_path = argv[1], sounds = argv[2], out = argv[3];
  std::filesystem::create_directories(out);
  Audio audio;

  // >>> soundpaint
  sp::Scene scene = sp::load_scene(scene_path).value();
  scene.sources.clear();  // every sound comes from OpenAL
  auto simulator = sp::create_cpu_simulator(sp::make_world(scene, sp::Config{}).value()).value();
  sp::openal::AdapterSettings settings;  // AL's listener is the player; AL space is the level's
  settings.rules = std::make_shared<const sp::CategoryRules>(sp::CategoryRules::parse(R"({"version": 1,
      "rules": [{"match": "footsteps/*", "category": "footsteps"}, {"match": "alarm/*", "category": "alarm"},
                {"match": "voice/*", "category": "voice"}]})")
                                                                 .value());
  sp::openal::Adapter adapter(simulator->scene(), settings);
  // <<< soundpaint

  const char* names[3] = {"footsteps/steps.wav", "alarm/siren.wav", "voice/announcement.wav"};
  const char* files[3] = {"footsteps.wav", "alarm.wav", "voice.wav"};
  ALuint buffers[3], sources[3];
  alGenBuffers(3, buffers);
  alGenSources(3, sources);
  for (int k = 0; k < 3; ++k) {
    const WavFile wav = read_wav16(sounds / files[k]);
    const ALenum format = wav.channels == 2 ? AL_FORMAT_STEREO16 : AL_FORMAT_MONO16;
    const auto bytes = static_cast<ALsizei>(wav.samples.size() * sizeof(std::int16_t));
    alBufferData(buffers[k], format, wav.samples.data(), bytes, wav.rate);
    // >>> soundpaint
    adapter.note_buffer_data(buffers[k], format, wav.samples.data(), bytes, wav.rate, names[k]).value();
    // <<< soundpaint
    alSourcei(sources[k], AL_BUFFER, static_cast<ALint>(buffers[k]));
  }
  // Footsteps and alarm loop from the start; the voice speaks at 1 s.
  const sp::Vec3 walker_from(8.0f, 0.3f, 2.5f), walker_to(5.0f, 0.3f, 6.5f);
  const sp::Vec3 alarm(12.0f, 2.5f, 4.0f), voice(7.5f, 1.6f, 7.0f);
  const sp::Vec3 player_from(1.5f, 1.7f, 1.5f), player_to(3.0f, 1.7f, 3.5f);
  alSourcei(sources[0], AL_LOOPING, AL_TRUE);
  alSourcei(sources[1], AL_LOOPING, AL_TRUE);
  alSource3f(sources[1], AL_POSITION, alarm.x, alarm.y, alarm.z);
  alSource3f(sources[2], AL_POSITION, voice.x, voice.y, voice.z);
  alSourcePlay(sources[0]);
  alSourcePlay(sources[1]);

  PictureWriter pictures(scene, simulator->world(), 960, 540);
  // Frames at the game's pace, 60 a second, so that what OpenAL plays (its
  // AL_SEC_OFFSET, which the cues follow) and the steps keep time.
  const auto start = std::chrono::steady_clock::now();
  for (int frame = 1; frame <= kFrames; ++frame) {
    std::this_thread::sleep_until(start + std::chrono::microseconds(frame * 1'000'000LL / 60));
    const float s = static_cast<float>(frame) / kFrames;
    const sp::Vec3 walker = lerp(walker_from, walker_to, s), player = lerp(player_from, player_to, s);
    alSource3f(sources[0], AL_POSITION, walker.x, walker.y, walker.z);
    alListener3f(AL_POSITION, player.x, player.y, player.z);
    if (frame == 60) alSourcePlay(sources[2]);
    // >>> soundpaint
    adapter.update().value();  // once a frame: AL's sources and listener
    simulator->step().value();
    // <<< soundpaint
    if (frame % 60 == 0) {
      char name[64];
      std::snprintf(name, sizeof name, "openal-frame-%03d.png", frame);
      pictures.write(out / name, *simulator, player, walker);
      std::map<std::string, int> cues;
      for (const sp::Indicator& i : simulator->live_indicators().value())
        cues[simulator->world().sources[i.source_id].category] += 1;
      std::printf("%s:", (out / name).c_str());
      for (const auto& [category, count] : cues) std::printf(" %s %d", category.c_str(), count);
      std::printf("\n");
    }
  }
  alDeleteSources(3, sources);
  alDeleteBuffers(3, buffers);
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "soundpaint_openal_example: %s\n", e.what());
  return 1;
}
