// The glTF 2.0 writer (io/gltf_writer.h), read back with tinygltf's own
// loader (independent of the writer's code): the base mesh and the morph
// deltas reproduce every frame to 1e-6, every POSITION accessor carries its
// true min and max, the faces are the input's, and the animation has one key
// per frame at k / fps with one-hot weights.
#include "shellspace/io/gltf_writer.h"

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "shellspace/geometry/procedural_shapes.h"
#include "tests/testing/test_support.h"

namespace shellspace {
namespace {

// The elements of an accessor as doubles (float or unsigned int
// components), respecting the view's byte stride.
std::vector<double> AccessorValues(const tinygltf::Model& model, int index) {
  const tinygltf::Accessor& accessor = model.accessors.at(index);
  const tinygltf::BufferView& view = model.bufferViews.at(accessor.bufferView);
  const tinygltf::Buffer& buffer = model.buffers.at(view.buffer);
  const int components = tinygltf::GetNumComponentsInType(accessor.type);
  const int size = tinygltf::GetComponentSizeInBytes(accessor.componentType);
  const size_t stride = view.byteStride ? view.byteStride : components * size;
  std::vector<double> values;
  for (size_t i = 0; i < accessor.count; ++i) {
    const unsigned char* element = buffer.data.data() + view.byteOffset +
                                   accessor.byteOffset + i * stride;
    for (int c = 0; c < components; ++c) {
      if (accessor.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT) {
        float v;
        std::memcpy(&v, element + c * size, sizeof(v));
        values.push_back(v);
      } else if (accessor.componentType ==
                 TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
        std::uint32_t v;
        std::memcpy(&v, element + c * size, sizeof(v));
        values.push_back(v);
      } else {
        ADD_FAILURE() << "unexpected component type " << accessor.componentType;
      }
    }
  }
  return values;
}

// The accessor's min and max are those of its values, per component.
void ExpectBounds(const tinygltf::Model& model, int index) {
  const tinygltf::Accessor& accessor = model.accessors.at(index);
  const std::vector<double> values = AccessorValues(model, index);
  ASSERT_EQ(accessor.minValues.size(), 3u);
  ASSERT_EQ(accessor.maxValues.size(), 3u);
  for (int c = 0; c < 3; ++c) {
    double lo = INFINITY, hi = -INFINITY;
    for (size_t i = c; i < values.size(); i += 3) {
      lo = std::min(lo, values[i]);
      hi = std::max(hi, values[i]);
    }
    EXPECT_EQ(accessor.minValues[c], lo) << "accessor " << index;
    EXPECT_EQ(accessor.maxValues[c], hi) << "accessor " << index;
  }
}

tinygltf::Model Load(const std::string& path) {
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string error, warning;
  EXPECT_TRUE(loader.LoadBinaryFromFile(&model, &error, &warning, path))
      << error;
  EXPECT_TRUE(error.empty()) << error;
  return model;
}

// A bending finger: 7 frames, the base bent by 0 .. 90 degrees and moved.
std::vector<Positions> BendingFinger(Faces* faces) {
  const Mesh finger = MakeFinger();
  *faces = finger.faces;
  std::vector<Positions> frames;
  for (int k = 0; k <= 6; ++k) {
    Positions p = k == 0 ? finger.positions
                         : BendAlongY(finger.positions, 4.0,
                                      k * std::acos(-1.0) / 12);
    p.col(2).array() += 0.1 * k;
    frames.push_back(p);
  }
  return frames;
}

TEST(GltfWriterTest, MorphTargetsReproduceTheFramesAndTheAnimationIsOneHot) {
  Faces faces;
  const std::vector<Positions> frames = BendingFinger(&faces);
  const std::string path = testing::TempDir() + "/finger.glb";
  GltfAnimationOptions options;
  options.frames_per_second = 5;
  WriteGltfMorphAnimation(path, frames, faces, options);
  const tinygltf::Model model = Load(path);

  EXPECT_EQ(model.asset.version, "2.0");
  ASSERT_EQ(model.meshes.size(), 1u);
  ASSERT_EQ(model.meshes[0].primitives.size(), 1u);
  const tinygltf::Primitive& primitive = model.meshes[0].primitives[0];
  EXPECT_EQ(primitive.mode, TINYGLTF_MODE_TRIANGLES);
  ASSERT_EQ(model.nodes.size(), 1u);
  EXPECT_EQ(model.nodes[0].mesh, 0);

  // Faces.
  const std::vector<double> indices = AccessorValues(model, primitive.indices);
  ASSERT_EQ(indices.size(), static_cast<size_t>(faces.size()));
  for (Eigen::Index i = 0; i < faces.size(); ++i) {
    ASSERT_EQ(indices[i], faces.data()[i]) << i;
  }

  // Base + deltas = frames.
  const int n = static_cast<int>(frames[0].rows());
  const int base_index = primitive.attributes.at("POSITION");
  const std::vector<double> base = AccessorValues(model, base_index);
  ASSERT_EQ(base.size(), 3u * n);
  ExpectBounds(model, base_index);
  ASSERT_EQ(primitive.targets.size(), frames.size() - 1);
  double worst = 0;
  for (int i = 0; i < 3 * n; ++i) {
    worst = std::max(worst, std::abs(base[i] - frames[0].data()[i]));
  }
  for (size_t t = 0; t < primitive.targets.size(); ++t) {
    const int index = primitive.targets[t].at("POSITION");
    ExpectBounds(model, index);
    const std::vector<double> delta = AccessorValues(model, index);
    ASSERT_EQ(delta.size(), 3u * n);
    for (int i = 0; i < 3 * n; ++i) {
      // The sum a viewer forms, in float.
      const float shown = static_cast<float>(base[i]) +
                          static_cast<float>(delta[i]);
      worst = std::max(worst, std::abs(shown - frames[t + 1].data()[i]));
    }
  }
  EXPECT_LT(worst, 1e-6) << "max |base + delta - frame|";
  char text[32];
  std::snprintf(text, sizeof(text), "%.3g", worst);
  RecordProperty("max_frame_error", text);
  EXPECT_EQ(model.meshes[0].weights, std::vector<double>(6, 0.0));
  ASSERT_TRUE(model.meshes[0].extras.Has("targetNames"));
  EXPECT_EQ(model.meshes[0].extras.Get("targetNames").Get(0).Get<std::string>(),
            "shape_001");

  // The animation: one key per frame, one-hot weights.
  ASSERT_EQ(model.animations.size(), 1u);
  const tinygltf::Animation& animation = model.animations[0];
  ASSERT_EQ(animation.channels.size(), 1u);
  EXPECT_EQ(animation.channels[0].target_node, 0);
  EXPECT_EQ(animation.channels[0].target_path, "weights");
  const tinygltf::AnimationSampler& sampler =
      animation.samplers.at(animation.channels[0].sampler);
  EXPECT_EQ(sampler.interpolation, "LINEAR");
  const std::vector<double> times = AccessorValues(model, sampler.input);
  ASSERT_EQ(times.size(), frames.size());
  const tinygltf::Accessor& input = model.accessors[sampler.input];
  EXPECT_EQ(input.minValues, std::vector<double>{0.0});
  EXPECT_EQ(input.maxValues, std::vector<double>{times.back()});
  const std::vector<double> weights = AccessorValues(model, sampler.output);
  const size_t targets = frames.size() - 1;
  ASSERT_EQ(weights.size(), frames.size() * targets);
  for (size_t k = 0; k < frames.size(); ++k) {
    EXPECT_FLOAT_EQ(times[k], k / 5.0);
    for (size_t t = 0; t < targets; ++t) {
      EXPECT_EQ(weights[k * targets + t], (k > 0 && t == k - 1) ? 1.0 : 0.0)
          << "key " << k << " target " << t;
    }
  }
}

TEST(GltfWriterTest, StepInterpolationAndASingleFrame) {
  Faces faces;
  std::vector<Positions> frames = BendingFinger(&faces);
  GltfAnimationOptions options;
  options.interpolation = GltfAnimationOptions::Interpolation::kStep;
  const std::string dir = testing::TempDir();
  WriteGltfMorphAnimation(dir + "/step.glb", frames, faces, options);
  const tinygltf::Model step = Load(dir + "/step.glb");
  ASSERT_EQ(step.animations.size(), 1u);
  EXPECT_EQ(step.animations[0].samplers[0].interpolation, "STEP");

  // One frame: the base mesh alone, no targets, no animation.
  frames.resize(1);
  WriteGltfMorphAnimation(dir + "/one.glb", frames, faces);
  const tinygltf::Model one = Load(dir + "/one.glb");
  EXPECT_TRUE(one.meshes.at(0).primitives.at(0).targets.empty());
  EXPECT_TRUE(one.animations.empty());
}

TEST(GltfWriterTest, BadInputIsAnInputErrorAndWritesNothing) {
  Faces faces;
  std::vector<Positions> frames = BendingFinger(&faces);
  const std::string dir = testing::TempDir();
  EXPECT_THROW(WriteGltfMorphAnimation(dir + "/a.glb", {}, faces),
               InputError);
  std::vector<Positions> short_frame = frames;
  short_frame[2] = frames[2].topRows(10);
  EXPECT_THROW(WriteGltfMorphAnimation(dir + "/a.glb", short_frame, faces),
               InputError);
  std::vector<Positions> nan_frame = frames;
  nan_frame[1](3, 1) = NAN;
  EXPECT_THROW(WriteGltfMorphAnimation(dir + "/a.glb", nan_frame, faces),
               InputError);
  Faces bad = faces;
  bad(0, 0) = static_cast<int>(frames[0].rows());
  EXPECT_THROW(WriteGltfMorphAnimation(dir + "/a.glb", frames, bad),
               InputError);
  GltfAnimationOptions zero_fps;
  zero_fps.frames_per_second = 0;
  EXPECT_THROW(WriteGltfMorphAnimation(dir + "/a.glb", frames, faces, zero_fps),
               InputError);
  // 1 / 1e300 rounds to float32 0: every key time would be 0, which glTF
  // refuses (times increase strictly). The twin: 1e30 frames per second
  // still has increasing float32 times.
  GltfAnimationOptions fast;
  fast.frames_per_second = 1e300;
  try {
    EncodeGltfMorphAnimation(frames, faces, fast);
    ADD_FAILURE() << "1e300 frames per second encoded";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("fall on one float32 time"),
              std::string::npos)
        << e.what();
  }
  fast.frames_per_second = 1e30;
  EXPECT_FALSE(EncodeGltfMorphAnimation(frames, faces, fast).empty());
  EXPECT_TRUE(testing::DirectoryListing(dir).empty());
}

}  // namespace
}  // namespace shellspace
