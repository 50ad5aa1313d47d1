// The OpenAL adapter from an installed soundpaint (find_package(soundpaint
// COMPONENTS openal)): a source played through OpenAL Soft's null output
// is mirrored and paints. Prints one line and exits 0 on success.
#include <AL/al.h>
#include <AL/alc.h>

#include <cstdio>
#include <cstdlib>
#include <vector>

#include <soundpaint/openal.h>

int main() {
  setenv("ALSOFT_DRIVERS", "null", 0);
  ALCdevice* device = alcOpenDevice(nullptr);
  ALCcontext* context = device != nullptr ? alcCreateContext(device, nullptr) : nullptr;
  if (context == nullptr || alcMakeContextCurrent(context) != ALC_TRUE) {
    std::fprintf(stderr, "consumer_openal: no OpenAL device\n");
    return 1;
  }
  sp::Scene scene;  // a floor
  scene.layer_names = {"concrete"};
  const float q[] = {-9, 0, -9, -9, 0, 9, 9, 0, 9, -9, 0, -9, 9, 0, 9, 9, 0, -9};
  for (int v = 0; v < 6; ++v) scene.vertices.push_back(sp::Vec3(q[3 * v], q[3 * v + 1], q[3 * v + 2]));
  scene.triangle_layers = {0, 0};
  sp::Config config;
  config.listener_position = sp::Vec3(0, 1, 0);
  auto sim = sp::create_cpu_simulator(sp::make_world(scene, config).value()).value();
  sp::openal::Adapter adapter(sim->scene());
  std::vector<ALshort> pcm(8000);
  for (std::size_t i = 0; i < pcm.size(); ++i) pcm[i] = static_cast<ALshort>(i % 2 == 0 ? 12000 : -12000);
  ALuint buffer = 0, source = 0;
  alGenBuffers(1, &buffer);
  alGenSources(1, &source);
  if (!adapter.buffer_data(buffer, AL_FORMAT_MONO16, pcm.data(), 16000, 16000, "step").ok()) return 1;
  alSourcei(source, AL_BUFFER, static_cast<ALint>(buffer));
  alSourcei(source, AL_LOOPING, AL_TRUE);
  alSource3f(source, AL_POSITION, 1.0f, 1.0f, 0.0f);
  alSourcePlay(source);
  if (!adapter.update().ok() || !sim->step().ok()) return 1;
  const std::size_t spots = sim->last_step_indicators().value().size();
  alDeleteSources(1, &source);
  alDeleteBuffers(1, &buffer);
  alcMakeContextCurrent(nullptr);
  alcDestroyContext(context);
  alcCloseDevice(device);
  if (spots == 0) {
    std::fprintf(stderr, "consumer_openal: the AL source painted nothing\n");
    return 1;
  }
  std::printf("consumer_openal: %zu spots from one AL source\n", spots);
  return 0;
}
