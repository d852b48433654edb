#include "shellspace/io/gltf_writer.h"

// tinygltf (Debian libtinygltf-dev, the compiled libtinygltf) is private to
// this file: no image support is needed for a mesh animation.
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <sstream>

#include "shellspace/geometry/named_values.h"
#include "shellspace/io/ascii_lowercase.h"
#include "shellspace/io/atomic_file.h"
#include "shellspace/io/frame_set_check.h"

namespace shellspace {
namespace {

// The binary buffer and the model's views and accessors on it.
class GltfBuilder {
 public:
  explicit GltfBuilder(tinygltf::Model* model) : model_(model) {}

  // A tightly packed view of `values` (4-byte components) with an
  // accessor of `count` elements of `type`; min/max per component if
  // `bounds`. Returns the accessor index.
  template <typename T>
  int AddAccessor(const std::vector<T>& values, int component_type, int type,
                  int components, int target, bool bounds) {
    static_assert(sizeof(T) == 4, "4-byte components only");
    std::vector<unsigned char>& data = buffer().data;
    const size_t offset = data.size();  // a multiple of 4
    data.resize(offset + values.size() * sizeof(T));
    std::memcpy(data.data() + offset, values.data(), values.size() * sizeof(T));

    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = offset;
    view.byteLength = values.size() * sizeof(T);
    if (target != 0) view.target = target;
    model_->bufferViews.push_back(view);

    tinygltf::Accessor accessor;
    accessor.bufferView = static_cast<int>(model_->bufferViews.size()) - 1;
    accessor.byteOffset = 0;
    accessor.componentType = component_type;
    accessor.count = values.size() / components;
    accessor.type = type;
    if (bounds) {
      accessor.minValues.assign(components,
                                std::numeric_limits<double>::infinity());
      accessor.maxValues.assign(components,
                                -std::numeric_limits<double>::infinity());
      for (size_t i = 0; i < values.size(); ++i) {
        const double v = static_cast<double>(values[i]);
        double& lo = accessor.minValues[i % components];
        double& hi = accessor.maxValues[i % components];
        lo = std::min(lo, v);
        hi = std::max(hi, v);
      }
    }
    model_->accessors.push_back(accessor);
    return static_cast<int>(model_->accessors.size()) - 1;
  }

 private:
  tinygltf::Buffer& buffer() {
    if (model_->buffers.empty()) model_->buffers.emplace_back();
    return model_->buffers[0];
  }
  tinygltf::Model* model_;
};


// The float32 of `value`, refused if not finite (beyond float's range).
float ToFloat32(double value, const std::string& what) {
  const float single = static_cast<float>(value);
  if (!std::isfinite(single)) {
    std::ostringstream text;
    text << "glTF export: " << what << " " << value
         << " is beyond float32's range (glTF stores float32)";
    throw InputError(text.str());
  }
  return single;
}

std::vector<float> ToFloats(const Positions& positions, size_t frame) {
  std::vector<float> out(positions.size());
  for (Eigen::Index i = 0; i < positions.size(); ++i) {
    out[i] = ToFloat32(positions.data()[i],
                       "frame " + std::to_string(frame) + " coordinate");
  }
  return out;
}

// The morph deltas of frames 1.. against the float32 base (every frame's
// float32 coordinates checked first).
std::vector<std::vector<float>> MorphDeltas(
    const std::vector<Positions>& frames, const std::vector<float>& base) {
  std::vector<std::vector<float>> deltas;
  for (size_t k = 1; k < frames.size(); ++k) {
    ToFloats(frames[k], k);
    std::vector<float> delta(base.size());
    for (size_t i = 0; i < base.size(); ++i) {
      delta[i] = ToFloat32(frames[k].data()[i] - static_cast<double>(base[i]),
                           "frame " + std::to_string(k) + " morph delta");
    }
    deltas.push_back(std::move(delta));
  }
  return deltas;
}

// The key time of each frame in seconds, refused where two fall on one
// float32 time.
std::vector<float> KeyTimes(size_t frame_count,
                            const GltfAnimationOptions& options) {
  std::vector<float> times(frame_count);
  for (size_t k = 0; k < frame_count; ++k) {
    times[k] = ToFloat32(k / options.frames_per_second, "key time (s)");
    // glTF's key times increase strictly; a rate so high that 1 / fps
    // rounds to 0 (or two times to one float) cannot be played.
    if (k > 0 && !(times[k] > times[k - 1])) {
      std::ostringstream message;
      message << "key times: frames " << k - 1 << " and " << k << " at "
              << options.frames_per_second
              << " frames per second fall on one float32 time (glTF needs "
                 "increasing times); use a lower rate";
      throw InputError(message.str());
    }
  }
  return times;
}

// The triangle indices of `faces` as an unsigned int accessor.
int AddIndices(const Faces& faces, GltfBuilder* builder) {
  std::vector<std::uint32_t> indices(faces.size());
  for (Eigen::Index i = 0; i < faces.size(); ++i) {
    indices[i] = static_cast<std::uint32_t>(faces.data()[i]);
  }
  return builder->AddAccessor(indices, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT,
                              TINYGLTF_TYPE_SCALAR, 1,
                              TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER, false);
}

// One morph target of `primitive` per delta, and their names shape_001...
tinygltf::Value::Array AddMorphTargets(
    const std::vector<std::vector<float>>& deltas, int targets,
    GltfBuilder* builder, tinygltf::Primitive* primitive) {
  tinygltf::Value::Array names;
  for (int t = 0; t < targets; ++t) {
    // Deltas against the float32 base: base + delta is frames[t + 1] up to
    // the rounding of delta and of the sum.
    const std::vector<float>& delta = deltas[t];
    std::map<std::string, int> target;
    target["POSITION"] = builder->AddAccessor(
        delta, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, 3,
        TINYGLTF_TARGET_ARRAY_BUFFER, true);
    primitive->targets.push_back(target);
    char name[32];
    std::snprintf(name, sizeof(name), "shape_%03d", t + 1);
    names.emplace_back(std::string(name));
  }
  return names;
}

// The mesh "shell" of `primitive` (zero weights and the target names when
// it has targets), and the node and default scene showing it.
void AddMeshNodeAndScene(const tinygltf::Primitive& primitive, int targets,
                         const tinygltf::Value::Array& names,
                         tinygltf::Model* model) {
  tinygltf::Mesh mesh;
  mesh.name = "shell";
  mesh.primitives.push_back(primitive);
  if (targets > 0) {
    mesh.weights.assign(targets, 0.0);
    tinygltf::Value::Object extras;
    extras["targetNames"] = tinygltf::Value(names);
    mesh.extras = tinygltf::Value(extras);
  }
  model->meshes.push_back(mesh);

  tinygltf::Node node;
  node.mesh = 0;
  node.name = "shell";
  model->nodes.push_back(node);
  tinygltf::Scene scene;
  scene.nodes.push_back(0);
  model->scenes.push_back(scene);
  model->defaultScene = 0;
}

// The animation "path" of the node's morph weights: at key time k only
// target k - 1 is weighted (1), frame 0 is the base.
void AddWeightAnimation(size_t frame_count, int targets,
                        const std::vector<float>& times,
                        const GltfAnimationOptions& options,
                        GltfBuilder* builder, tinygltf::Model* model) {
  std::vector<float> weights(frame_count * targets, 0.0f);
  for (size_t k = 1; k < frame_count; ++k) {
    weights[k * targets + (k - 1)] = 1.0f;
  }
  tinygltf::AnimationSampler sampler;
  sampler.input = builder->AddAccessor(times, TINYGLTF_COMPONENT_TYPE_FLOAT,
                                       TINYGLTF_TYPE_SCALAR, 1, 0, true);
  sampler.output = builder->AddAccessor(weights, TINYGLTF_COMPONENT_TYPE_FLOAT,
                                        TINYGLTF_TYPE_SCALAR, 1, 0, false);
  sampler.interpolation =
      options.interpolation == GltfAnimationOptions::Interpolation::kStep
          ? "STEP"
          : "LINEAR";
  tinygltf::AnimationChannel channel;
  channel.sampler = 0;
  channel.target_node = 0;
  channel.target_path = "weights";
  tinygltf::Animation animation;
  animation.name = "path";
  animation.samplers.push_back(sampler);
  animation.channels.push_back(channel);
  model->animations.push_back(animation);
}

}  // namespace

GltfAnimationOptions::Interpolation ParseGltfInterpolation(
    const std::string& text, const std::string& name) {
  using Interpolation = GltfAnimationOptions::Interpolation;
  static constexpr NamedValue<Interpolation> kNames[] = {
      {Interpolation::kLinear, "linear"}, {Interpolation::kStep, "step"}};
  return ParseNamedValue(kNames, text, name);
}

std::string EncodeGltfMorphAnimation(const std::vector<Positions>& frames,
                                     const Faces& faces,
                                     const GltfAnimationOptions& options) {
  CheckFrameSet(frames, faces, "glTF export");
  if (!(options.frames_per_second > 0) ||
      !std::isfinite(options.frames_per_second)) {
    throw InputError("glTF export: frames per second must be > 0");
  }
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "shellspace";
  GltfBuilder builder(&model);

  tinygltf::Primitive primitive;
  primitive.mode = TINYGLTF_MODE_TRIANGLES;
  const std::vector<float> base = ToFloats(frames[0], 0);
  // Every float32 value checked before any is encoded: the deltas and the
  // key times too.
  const std::vector<std::vector<float>> deltas = MorphDeltas(frames, base);
  const std::vector<float> times = KeyTimes(frames.size(), options);
  primitive.attributes["POSITION"] = builder.AddAccessor(
      base, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, 3,
      TINYGLTF_TARGET_ARRAY_BUFFER, true);
  primitive.indices = AddIndices(faces, &builder);

  const int targets = static_cast<int>(frames.size()) - 1;
  const tinygltf::Value::Array names =
      AddMorphTargets(deltas, targets, &builder, &primitive);
  AddMeshNodeAndScene(primitive, targets, names, &model);
  if (targets > 0) {
    AddWeightAnimation(frames.size(), targets, times, options, &builder,
                       &model);
  }

  std::ostringstream stream;
  tinygltf::TinyGLTF writer;
  if (!writer.WriteGltfSceneToStream(&model, stream, false, true)) {
    throw InputError("glTF export: tinygltf could not encode the model");
  }
  return stream.str();
}

void CheckGltfFileName(const std::string& path, const std::string& name) {
  const std::string lower = AsciiLowercase(path);
  if (lower.size() <= 4 || lower.compare(lower.size() - 4, 4, ".glb") != 0) {
    throw InputError(name + " " + path +
                     ": the file written is binary glTF; name it .glb" +
                     (lower.size() > 5 &&
                              lower.compare(lower.size() - 5, 5, ".gltf") == 0
                          ? " (.gltf is the JSON container)"
                          : ""));
  }
}

void WriteGltfMorphAnimation(const std::string& path,
                             const std::vector<Positions>& frames,
                             const Faces& faces,
                             const GltfAnimationOptions& options) {
  CheckGltfFileName(path, "glTF export:");
  WriteFileAtomically(path, EncodeGltfMorphAnimation(frames, faces, options));
}

}  // namespace shellspace
