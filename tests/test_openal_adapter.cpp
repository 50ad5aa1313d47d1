// The OpenAL adapter (soundpaint/openal.h) against OpenAL Soft on its null
// output (ALSOFT_DRIVERS=null: no sound card, the mixer still runs): a game
// that makes only AL calls plus one adapter call per buffer and one per
// frame gets cues that follow its sources as they play, move, stop, are
// deleted and reused, at the energy the signal law gives its samples, on
// both backends; misuse gets an error naming it.
#include <AL/al.h>
#include <AL/alc.h>

#include <cmath>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "soundpaint/openal.h"
#include "support/backend_cases.h"
#include "support/gpu_environment.h"
#include "support/scene_builder.h"

namespace sp {
namespace {

// One AL device and context for the binary, made current.
class AlContext {
 public:
  AlContext() {
    setenv("ALSOFT_DRIVERS", "null", 0);  // headless: CI has no sound card
    device_ = alcOpenDevice(nullptr);
    if (device_ != nullptr) context_ = alcCreateContext(device_, nullptr);
    if (context_ != nullptr) alcMakeContextCurrent(context_);
  }
  ~AlContext() {
    alcMakeContextCurrent(nullptr);
    if (context_ != nullptr) alcDestroyContext(context_);
    if (device_ != nullptr) alcCloseDevice(device_);
  }
  bool ok() const { return context_ != nullptr; }
  ALCcontext* context() const { return context_; }

 private:
  ALCdevice* device_ = nullptr;
  ALCcontext* context_ = nullptr;
};

AlContext& al() {
  static AlContext context;
  return context;
}

// One second of a 16-bit square wave of amplitude `amplitude` (of 32768).
std::vector<ALshort> square16(int amplitude) {
  std::vector<ALshort> out(22050);
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = static_cast<ALshort>(i % 2 == 0 ? amplitude : -amplitude);
  return out;
}

double law_e0(int amplitude) { return (60.0 + 20.0 * std::log10(amplitude / 32768.0)) / 60.0; }

class OpenAlAdapter : public test::GpuTest, public ::testing::WithParamInterface<test::BackendCase> {
 protected:
  void SetUp() override {
    test::GpuTest::SetUp();
    if (IsSkipped() || HasFatalFailure()) return;
    ASSERT_TRUE(al().ok()) << "no OpenAL device, even the null one";
    ASSERT_EQ(alcMakeContextCurrent(al().context()), ALC_TRUE);
    Scene scene = test::closed_room();
    scene.sources.clear();  // every source comes from AL
    Config config;
    config.ray_budget = 200;
    config.air_attenuation = 0.1f;
    config.listener_position = Vec3(-2.0f, 1.5f, 0.0f);
    config.cpu_traversal = GetParam().traversal;
    World world = make_world(scene, config).value();
    sim_ = make_simulator(std::move(world), GetParam().backend);
    make_adapter();
    alGenBuffers(2, buffers_);
    alGenSources(1, &source_);
    alListener3f(AL_POSITION, -2.0f, 1.5f, 0.0f);
  }
  void TearDown() override {
    alDeleteSources(1, &source_);
    alDeleteBuffers(2, buffers_);
    test::GpuTest::TearDown();
  }
  void make_adapter() {
    openal::AdapterSettings settings;
    auto rules = CategoryRules::parse(R"({"version": 1, "rules": [
        {"match": "sound/player/footsteps/*", "category": "footsteps"},
        {"match": "sound/misc/*", "ignore": true}], "default": "sound"})");
    settings.rules = std::make_shared<const CategoryRules>(rules.value());
    adapter_ = std::make_unique<openal::Adapter>(sim_->scene(), settings);
  }
  // Uploads a one-second square wave, AL's call and the adapter's beside it.
  void upload(ALuint buffer, int amplitude, const char* name) {
    const std::vector<ALshort> pcm = square16(amplitude);
    const auto bytes = static_cast<ALsizei>(pcm.size() * sizeof(ALshort));
    alBufferData(buffer, AL_FORMAT_MONO16, pcm.data(), bytes, 22050);
    ASSERT_TRUE(adapter_->note_buffer_data(buffer, AL_FORMAT_MONO16, pcm.data(), bytes, 22050, name).ok());
  }
  // A frame: the adapter's update, then one step; the step's indicators.
  std::vector<Indicator> frame() {
    auto report = adapter_->update();
    EXPECT_TRUE(report.ok()) << (report.ok() ? "" : report.error().message);
    EXPECT_TRUE(sim_->step().ok());
    return sim_->last_step_indicators().value();
  }
  std::unique_ptr<Simulator> sim_;
  std::unique_ptr<openal::Adapter> adapter_;
  ALuint buffers_[2] = {0, 0};
  ALuint source_ = 0;
};

TEST_P(OpenAlAdapter, FollowsASourceThatPlaysMovesStopsAndIsDeleted) {
  upload(buffers_[0], 16384, "sound/player/footsteps/boot1.wav");  // -6.02 dB
  alSourcei(source_, AL_BUFFER, static_cast<ALint>(buffers_[0]));
  alSourcei(source_, AL_LOOPING, AL_TRUE);
  alSource3f(source_, AL_POSITION, 0.0f, 1.5f, 0.0f);
  EXPECT_TRUE(frame().empty());  // not playing yet: nothing mirrored
  EXPECT_FALSE(adapter_->source_id(source_).has_value());

  alSourcePlay(source_);
  const std::vector<Indicator> playing = frame();
  ASSERT_FALSE(playing.empty());
  const std::uint32_t id = adapter_->source_id(source_).value();
  EXPECT_EQ(sim_->world().sources[id].category, "footsteps");
  for (const Indicator& i : playing) {
    EXPECT_EQ(i.source_id, id);
    if (i.bounces == 0 && i.penetrations == 0) {
      EXPECT_NEAR(i.energy + i.path_length * 0.1f, law_e0(16384), 1e-5);
    }
  }

  alSource3f(source_, AL_POSITION, 1.0f, 1.0f, -1.0f);  // moved
  frame();
  EXPECT_EQ(sim_->world().sources[id].position, Vec3(1.0f, 1.0f, -1.0f));

  // Half the gain: 6.02 dB lower, by the law.
  alSourcef(source_, AL_GAIN, 0.5f);
  for (const Indicator& i : frame()) {
    if (i.bounces == 0 && i.penetrations == 0) {
      EXPECT_NEAR(i.energy + i.path_length * 0.1f, law_e0(8192), 1e-5);
    }
  }

  alSourceStop(source_);
  frame();  // the stop is read here and applies from the next step
  EXPECT_TRUE(frame().empty());

  alDeleteSources(1, &source_);
  ASSERT_TRUE(adapter_->update().ok());
  ASSERT_TRUE(sim_->step().ok());
  EXPECT_FALSE(sim_->scene().has_source(id));
  EXPECT_FALSE(adapter_->source_id(source_).has_value());
  alGenSources(1, &source_);  // for TearDown
}

TEST_P(OpenAlAdapter, ABurstPaintsMoreThanAWhisperAndSilenceNothing) {
  upload(buffers_[0], 16384, "sound/weapons/shot.wav");  // -6 dB: E0 0.90, reach 8.5 m
  upload(buffers_[1], 328, "sound/voice/whisper.wav");   // -40 dB: E0 0.33, reach 2.8 m
  alSourcei(source_, AL_BUFFER, static_cast<ALint>(buffers_[0]));
  alSourcei(source_, AL_LOOPING, AL_TRUE);
  alSource3f(source_, AL_POSITION, 0.0f, 1.5f, 0.0f);
  alSourcePlay(source_);
  const std::size_t burst = frame().size();
  // The same AL source reused for another buffer: described anew.
  alSourceStop(source_);
  alSourcei(source_, AL_BUFFER, static_cast<ALint>(buffers_[1]));
  alSourcePlay(source_);
  const std::vector<Indicator> whisper = frame();
  ASSERT_FALSE(whisper.empty());
  EXPECT_GT(burst, whisper.size());
  const float reach = static_cast<float>((law_e0(328) - 0.05) / 0.1);
  for (const Indicator& i : whisper) EXPECT_LE(i.path_length, reach + 1e-4f);
  EXPECT_EQ(sim_->world().sources[adapter_->source_id(source_).value()].category, "sound");  // the rules' default
  // Silence: a buffer of zeros plays, nothing is painted.
  std::vector<ALshort> zeros(4410, 0);
  alSourceStop(source_);
  alSourcei(source_, AL_BUFFER, 0);
  alBufferData(buffers_[1], AL_FORMAT_MONO16, zeros.data(), 8820, 22050);
  ASSERT_TRUE(adapter_->note_buffer_data(buffers_[1], AL_FORMAT_MONO16, zeros.data(), 8820, 22050, "quiet").ok());
  alSourcei(source_, AL_BUFFER, static_cast<ALint>(buffers_[1]));
  alSourcePlay(source_);
  frame();
  EXPECT_TRUE(frame().empty());
}

TEST_P(OpenAlAdapter, MisuseGetsAnErrorNamingIt) {
  std::vector<ALshort> pcm = square16(1000);
  // A format it cannot read.
  auto bad = adapter_->note_buffer_data(buffers_[0], 0x1234, pcm.data(), 100, 22050, "x.wav");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("buffer " + std::to_string(buffers_[0]) + " (\"x.wav\"): format 0x1234"),
            std::string::npos)
      << bad.error().message;
  EXPECT_FALSE(adapter_->note_buffer_data(buffers_[0], AL_FORMAT_MONO16, pcm.data(), 3, 22050, "x").ok());
  // A buffer never described, playing.
  alBufferData(buffers_[1], AL_FORMAT_MONO16, pcm.data(), 2000, 22050);
  alSourcei(source_, AL_BUFFER, static_cast<ALint>(buffers_[1]));
  alSourcei(source_, AL_LOOPING, AL_TRUE);
  alSourcePlay(source_);
  auto unknown = adapter_->update();
  ASSERT_FALSE(unknown.ok());
  EXPECT_NE(unknown.error().message.find("plays buffer " + std::to_string(buffers_[1]) + ", which was never given"),
            std::string::npos)
      << unknown.error().message;
  alSourceStop(source_);
  // Ignored by the rules: never painted, no error.
  ASSERT_TRUE(
      adapter_->note_buffer_data(buffers_[1], AL_FORMAT_MONO16, pcm.data(), 2000, 22050, "sound/misc/menu1.wav").ok());
  alSourcePlay(source_);
  EXPECT_TRUE(frame().empty());
  EXPECT_FALSE(adapter_->source_id(source_).has_value());
  // No current context.
  alcMakeContextCurrent(nullptr);
  auto none = adapter_->update();
  alcMakeContextCurrent(al().context());
  ASSERT_FALSE(none.ok());
  EXPECT_NE(none.error().message.find("no current AL context"), std::string::npos);
}

INSTANTIATE_TEST_SUITE_P(Backends, OpenAlAdapter, ::testing::ValuesIn(test::backend_cases()), test::backend_case_name);

}  // namespace
}  // namespace sp
