// Private to the scene loader: acoustic data attached to glTF nodes.
//
//   node.extras.acoustic_layer   string: the layer of the node's triangles
//   node.extras.sound_source     object with a config source's fields
//                                (color, category, max_distance, loudness,
//                                duration, interval, phase); strict: unknown
//                                keys, wrong types and out-of-range values fail
//   node.extensions.KHR_audio_emitter.emitter
//                                index into the root KHR_audio_emitter.emitters;
//                                a positional emitter becomes a source with
//                                gain -> loudness, positional.maxDistance ->
//                                max_distance, emitter name -> category
//
// Other extras keys are left alone: extras belong to every tool in the chain.
#pragma once

#include <tiny_gltf.h>

#include <optional>
#include <string>
#include <vector>

#include "soundpaint/config.h"

namespace sp::scene_detail {

// One KHR_audio_emitter emitter, reduced to what a source needs.
struct AudioEmitter {
  bool positional = false;            // global emitters have no place and are ignored
  std::string name;                   // "" when absent
  std::optional<float> gain;          // >= 0
  std::optional<float> max_distance;  // positional.maxDistance, >= 0
};

// The root extensions.KHR_audio_emitter.emitters, in file order (empty when
// the extension is absent). Throws sp::Exception on a malformed emitter.
std::vector<AudioEmitter> read_audio_emitters(const tinygltf::Model& model);

struct NodeAcoustics {
  std::optional<std::string> layer;  // extras.acoustic_layer
  // extras.sound_source first, then the node's positional emitter: a node
  // carrying both is two sources. `name` is the node's name; `position` is
  // left for the caller, who knows the world transform.
  std::vector<SourceDesc> sources;
};

// Reads node `node_index`'s extras and KHR_audio_emitter reference. Throws
// sp::Exception naming the node and the key on any malformed value.
NodeAcoustics read_node_acoustics(const tinygltf::Model& model, int node_index,
                                  const std::vector<AudioEmitter>& emitters);

}  // namespace sp::scene_detail
