// The OpenAL trace shim (openal/trace/) as a game meets it: loaded as its
// OpenAL library (dlopen, as ioquake3's s_alDriver does), every call
// forwarded to OpenAL Soft (null output), and the trace it writes read back
// by soundpaint's own reader: the buffer named by the hash of its bytes,
// with its envelope; play, move, stop, delete and the listener in order;
// the summary line last.
#include <AL/al.h>
#include <AL/alc.h>
#include <dlfcn.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "events/event_trace.h"
#include "support/test_directory.h"

namespace sp {
namespace {

// The shim's functions, looked up by name as a game's loader does.
struct Shim {
  void* handle = nullptr;
  template <class Fn>
  Fn* get(const char* name) {
    return reinterpret_cast<Fn*>(dlsym(handle, name));
  }
};

std::uint64_t fnv1a64(const void* data, std::size_t size) {
  std::uint64_t h = 1469598103934665603ull;
  for (std::size_t i = 0; i < size; ++i) h = (h ^ static_cast<const unsigned char*>(data)[i]) * 1099511628211ull;
  return h;
}

class AlTraceShim : public test::TestDirectory {};

TEST_F(AlTraceShim, RecordsWhatTheGameDoesAndForwardsIt) {
  const std::string trace = (dir_ / "trace.jsonl").string();
  // A 0.05 s square wave at half scale: -6.02 dB in every 10 ms hop.
  std::vector<ALshort> pcm(1100);
  for (std::size_t i = 0; i < pcm.size(); ++i) pcm[i] = static_cast<ALshort>(i % 2 == 0 ? 16384 : -16384);
  char digest[17];
  std::snprintf(digest, sizeof digest, "%016llx",
                static_cast<unsigned long long>(fnv1a64(pcm.data(), pcm.size() * sizeof(ALshort))));
  const std::string names = write("names.tsv", std::string(digest) + "\tsound/player/footsteps/boot1.wav\n");
  setenv("SOUNDPAINT_TRACE", trace.c_str(), 1);
  setenv("SOUNDPAINT_SOUND_NAMES", names.c_str(), 1);
  setenv("ALSOFT_DRIVERS", "null", 0);

  Shim shim{dlopen(SP_AL_TRACE_SHIM, RTLD_NOW | RTLD_LOCAL)};
  ASSERT_NE(shim.handle, nullptr) << dlerror();
  auto open_device = shim.get<decltype(alcOpenDevice)>("alcOpenDevice");
  auto create_context = shim.get<decltype(alcCreateContext)>("alcCreateContext");
  auto make_current = shim.get<decltype(alcMakeContextCurrent)>("alcMakeContextCurrent");
  auto destroy_context = shim.get<decltype(alcDestroyContext)>("alcDestroyContext");
  auto close_device = shim.get<decltype(alcCloseDevice)>("alcCloseDevice");
  auto gen_buffers = shim.get<decltype(alGenBuffers)>("alGenBuffers");
  auto buffer_data = shim.get<decltype(alBufferData)>("alBufferData");
  auto gen_sources = shim.get<decltype(alGenSources)>("alGenSources");
  auto source_i = shim.get<decltype(alSourcei)>("alSourcei");
  auto source_3f = shim.get<decltype(alSource3f)>("alSource3f");
  auto source_fv = shim.get<decltype(alSourcefv)>("alSourcefv");
  auto source_f = shim.get<decltype(alSourcef)>("alSourcef");
  auto play = shim.get<decltype(alSourcePlay)>("alSourcePlay");
  auto stop = shim.get<decltype(alSourceStop)>("alSourceStop");
  auto delete_sources = shim.get<decltype(alDeleteSources)>("alDeleteSources");
  auto listener_fv = shim.get<decltype(alListenerfv)>("alListenerfv");
  auto get_source_i = shim.get<decltype(alGetSourcei)>("alGetSourcei");
  auto is_source = shim.get<decltype(alIsSource)>("alIsSource");  // a pass-through one
  ASSERT_TRUE(open_device && create_context && make_current && destroy_context && close_device && gen_buffers &&
              buffer_data && gen_sources && source_i && source_3f && source_fv && source_f && play && stop &&
              delete_sources && listener_fv && get_source_i && is_source);

  ALCdevice* device = open_device(nullptr);
  ASSERT_NE(device, nullptr);
  ALCcontext* context = create_context(device, nullptr);
  ASSERT_EQ(make_current(context), ALC_TRUE);
  ALuint buffer = 0, source = 0;
  gen_buffers(1, &buffer);
  buffer_data(buffer, AL_FORMAT_MONO16, pcm.data(), static_cast<ALsizei>(pcm.size() * sizeof(ALshort)), 22050);
  gen_sources(1, &source);
  const float at[3] = {64, -32, 16}, there[3] = {96, -32, 16}, ear[3] = {0, 0, 48};
  listener_fv(AL_POSITION, ear);
  source_i(source, AL_BUFFER, static_cast<ALint>(buffer));
  source_i(source, AL_LOOPING, AL_TRUE);
  source_fv(source, AL_POSITION, at);
  source_f(source, AL_GAIN, 0.5f);
  play(source);
  ALint state = 0;
  get_source_i(source, AL_SOURCE_STATE, &state);
  EXPECT_EQ(state, AL_PLAYING);  // forwarded to the real OpenAL
  EXPECT_EQ(is_source(source), AL_TRUE);
  source_3f(source, AL_POSITION, there[0], there[1], there[2]);
  stop(source);
  play(source);
  delete_sources(1, &source);
  make_current(nullptr);
  destroy_context(context);
  close_device(device);  // writes the summary and closes the trace
  dlclose(shim.handle);
  unsetenv("SOUNDPAINT_TRACE");

  using K = events::TraceEvent::Kind;
  const std::vector<events::TraceEvent> events = events::load_trace(trace);
  ASSERT_EQ(events.size(), 7u);
  EXPECT_EQ(events[0].kind, K::Buffer);
  EXPECT_EQ(events[0].name, "sound/player/footsteps/boot1.wav");
  EXPECT_NEAR(events[0].signal->duration(), 0.05, 1e-9);                  // 5 hops of 10 ms
  EXPECT_NEAR(events[0].signal->level_db(0.0, 0.01, false), -6.0, 0.05);  // written to 0.1 dB
  EXPECT_EQ(events[1].kind, K::Listener);
  EXPECT_EQ(events[1].position, Vec3(0, 0, 48));
  EXPECT_EQ(events[2].kind, K::Play);
  EXPECT_EQ(events[2].id, source);
  EXPECT_EQ(events[2].buffer, buffer);
  EXPECT_EQ(events[2].position, Vec3(64, -32, 16));
  EXPECT_EQ(events[2].gain, 0.5f);
  EXPECT_TRUE(events[2].loop);
  EXPECT_EQ(events[3].kind, K::Move);
  EXPECT_EQ(events[3].position, Vec3(96, -32, 16));
  EXPECT_EQ(events[4].kind, K::Stop);
  EXPECT_EQ(events[5].kind, K::Play);
  EXPECT_EQ(events[6].kind, K::Delete);
  std::ifstream in(trace);
  std::string line, last;
  while (std::getline(in, line)) last = line;
  EXPECT_NE(last.find("\"type\":\"summary\""), std::string::npos) << last;
}

}  // namespace
}  // namespace sp
