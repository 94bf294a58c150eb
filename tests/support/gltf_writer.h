// Building glTF models in tests for tinygltf's writer: raw data appended to the
// model's one buffer as a buffer view and an accessor over it, and image textures.
#pragma once
#include <tiny_gltf.h>
#include <cstddef>
#include <string>

namespace penumbra {

// Appends `bytes` of `data` to buffers[0] (padded to 4 bytes, as the spec aligns
// views) and an accessor of `count` elements over them; returns the accessor's index.
inline int addAccessor(tinygltf::Model& m, const void* data, size_t bytes, int componentType, int type, size_t count) {
  tinygltf::Buffer& buffer = m.buffers[0];
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = buffer.data.size();
  view.byteLength = bytes;
  const auto* p = static_cast<const unsigned char*>(data);
  buffer.data.insert(buffer.data.end(), p, p + bytes);
  while (buffer.data.size() % 4) buffer.data.push_back(0);
  m.bufferViews.push_back(view);
  tinygltf::Accessor a;
  a.bufferView = static_cast<int>(m.bufferViews.size()) - 1;
  a.componentType = componentType;
  a.type = type;
  a.count = count;
  m.accessors.push_back(a);
  return static_cast<int>(m.accessors.size()) - 1;
}

// Adds `uri` (an image file beside the model) as an image and a texture over it;
// returns the texture's index.
inline int addTexture(tinygltf::Model& m, const std::string& uri) {
  tinygltf::Image image;
  image.uri = uri;
  m.images.push_back(image);
  tinygltf::Texture texture;
  texture.source = static_cast<int>(m.images.size()) - 1;
  m.textures.push_back(texture);
  return static_cast<int>(m.textures.size()) - 1;
}

}  // namespace penumbra
