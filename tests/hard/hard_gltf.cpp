// Hard cases, class "glTF" (bounds and bombs): sizes and offsets that wrap, index
// types, JSON nesting, memory estimates and node graphs that multiply instances.
#include "hard/hard_gltf_support.h"

using namespace penumbra;
using namespace penumbra::hard_gltf;

// The unmodified triangle loads (so each refusal below is the edit's doing).
TEST(HardGltf, TheBaseTriangleLoads) {
  const ScratchDir dir;
  const fs::path file = dir.write("model.gltf", triangle().dump());
  EXPECT_EQ(refusal(file), "");
  const LoadedModel m = loadModel(file.string());
  ASSERT_EQ(m.meshes.size(), 1u);
  EXPECT_EQ(m.meshes[0].normals.size(), 3u);
  EXPECT_EQ(m.meshes[0].uvs.size(), 3u);
}

// Sizes and offsets that wrap 64-bit arithmetic once passed the bounds check and
// read or wrote far outside the buffer; now every one is refused.
TEST(HardGltf, WrappingSizesAndOffsetsAreRefused) {
  const ScratchDir dir;
  json j = triangle();
  j["accessors"][0]["count"] = 6148914691236517206ull;  // x 3 doubles wraps to 2; x 12 bytes wraps
  expectRefused(dir, j, {"accessors[0].count"});
  j = triangle();
  j["accessors"][0]["byteOffset"] = 18446744073709551608ull;  // + 12 wraps to 4
  expectRefused(dir, j, {"accessors[0].byteOffset"});
  j = triangle();
  j["bufferViews"][0]["byteOffset"] = 18446744073709551612ull;  // + 36 wraps to 32
  expectRefused(dir, j, {"bufferViews[0]"});
  j = triangle();
  j["accessors"][0]["count"] = 4;  // one element past its view
  expectRefused(dir, j, {"accessors[0].count", "reaches past the end of its buffer view"});
  j = triangle();
  j["bufferViews"][0]["byteStride"] = 4;  // below the 12-byte element: elements overlap
  expectRefused(dir, j, {"bufferViews[0].byteStride"});
  j = triangle();
  j["bufferViews"][0]["byteStride"] = 256;
  expectRefused(dir, j, {"bufferViews[0].byteStride"});
}

// Indices are the spec's unsigned integer types, each naming a vertex.
TEST(HardGltf, IndicesAreUnsignedIntegersNamingVertices) {
  const ScratchDir dir;
  json j = triangle();
  j["buffers"][0] = {{"byteLength", 108}, {"uri", dataUri(kVertexData + bytesOf<float>({0, 1, 2}))}};
  j["bufferViews"][3]["byteLength"] = 12;
  j["accessors"][3]["componentType"] = 5126;  // 0.0, 1.0, 2.0 as FLOAT indices
  expectRefused(dir, j, {"accessors[3]", "indices must be a SCALAR of UNSIGNED_BYTE"});
  j = triangle();
  j["accessors"][3]["componentType"] = 5120;  // BYTE: could be negative
  expectRefused(dir, j, {"accessors[3]", "indices must be"});
  j = triangle();
  j["accessors"][3]["normalized"] = true;
  expectRefused(dir, j, {"accessors[3]", "indices must be"});
  j = triangle();
  j["buffers"][0]["uri"] = dataUri(kVertexData + std::string("\0\1\3\0", 4));
  expectRefused(dir, j, {"accessors[3]", "index 3", "does not have"});
}

// 100,000 nested arrays under extras overflowed the stack inside tinygltf's parser.
TEST(HardGltf, DeepJsonIsRefusedBeforeParsing) {
  const ScratchDir dir;
  std::string text = triangle().dump();
  text.insert(1, "\"extras\": " + std::string(100000, '[') + std::string(100000, ']') + ", ");
  const fs::path file = dir.write("model.gltf", text);
  const std::string what = refusal(file);
  EXPECT_NE(what.find("nest deeper than 64"), std::string::npos) << what;
  // Brackets inside strings are not nesting.
  json j = triangle();
  j["extras"] = std::string(1000, '[');
  EXPECT_EQ(refusal(dir.write("model.gltf", j.dump())), "");
}

// A file of under 1 MB whose 20,000 primitives each reuse one 10,000-vertex
// accessor asked for ~22 GB of meshes before any check.
TEST(HardGltf, MeshBytesAreEstimatedBeforeAllocating) {
  const ScratchDir dir;
  json j = triangle();
  j["buffers"][0] = {{"byteLength", 120000}, {"uri", dataUri(std::string(120000, '\0'))}};
  j["bufferViews"] = {{{"buffer", 0}, {"byteLength", 120000}}};
  j["accessors"] = {{{"bufferView", 0}, {"componentType", 5126}, {"count", 10000}, {"type", "VEC3"}}};
  j["meshes"][0]["primitives"] = json::array();
  for (int i = 0; i < 20000; ++i) j["meshes"][0]["primitives"].push_back({{"attributes", {{"POSITION", 0}}}});
  ASSERT_LT(j.dump().size(), 1000000u);
  const auto start = std::chrono::steady_clock::now();
  expectRefused(dir, j, {"needs ~20.9 GiB for its meshes but --max-memory is 2.0 GiB"}, LoadLimits{2ull << 30, "--max-memory"});
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 2.0);
  // Instances count: the triangle under 3 nodes needs three times one.
  j = triangle();
  j["nodes"] = {{{"children", {1, 2, 3}}}, {{"mesh", 0}}, {{"mesh", 0}}, {{"mesh", 0}}};
  const fs::path file = dir.write("model.gltf", j.dump());
  EXPECT_EQ(refusal(file, LoadLimits{1'000'000, "--max-memory"}), "");
  EXPECT_EQ(loadModel(file.string()).meshes.size(), 3u);
}

// Nodes listed twice as children were instanced 2^depth times; cycles recursed.
TEST(HardGltf, TheNodeGraphMustBeAForest) {
  const ScratchDir dir;
  json j = triangle();
  j["nodes"] = json::array();
  for (int i = 0; i < 40; ++i) j["nodes"].push_back({{"children", {i + 1, i + 1}}});
  j["nodes"].push_back({{"mesh", 0}});
  expectRefused(dir, j, {"nodes[0].children[1]", "node 1 is already a child of node 0"});
  j["nodes"] = {{{"children", {1}}}, {{"children", {2}}, {"mesh", 0}}, {{"children", {1}}}};
  expectRefused(dir, j, {"nodes[2].children[0]", "already a child"});
  j["nodes"] = {{{"mesh", 0}}, {{"children", {2}}}, {{"children", {1}}}};  // a cycle no scene reaches
  expectRefused(dir, j, {"cycle"});
  j["nodes"] = {{{"children", {0}}, {"mesh", 0}}};
  expectRefused(dir, j, {"nodes[0].children[0]", "its own child"});
  j["nodes"] = {{{"children", {1}}}, {{"mesh", 0}}};
  j["scenes"][0]["nodes"] = {0, 1};  // node 1 as a root and as a child
  expectRefused(dir, j, {"scenes[0].nodes[1]", "not a root"});
  j["scenes"][0]["nodes"] = {0, 0};
  expectRefused(dir, j, {"scenes[0].nodes[1]", "listed twice"});
}
