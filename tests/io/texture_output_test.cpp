// The texture parts of the writers: glTF's TEXCOORD_0, TANGENT and material
// textures (read back through geodual's reader, which samples the base colour
// texture at the vertices), OBJ's vt lines and material library, PLY's
// TextureFile comment, and the PNG and JPEG images.

#include "geodual/io/gltf.hpp"
#include "geodual/io/image_file.hpp"
#include "geodual/io/read_mesh.hpp"
#include "geodual/io/write_mesh.hpp"
#include "io_test_files.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

namespace geodual::io {
namespace {
namespace fs = std::filesystem;

TriangleMesh unit_quad() {
  return {.vertices = VertexMatrix{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}},
          .faces = FaceMatrix{{0, 1, 2}, {0, 2, 3}}};
}

TextureImage flat_image(int size, std::uint8_t r, std::uint8_t g, std::uint8_t b) {
  TextureImage image{.width = size, .height = size, .channels = 3};
  for (int i = 0; i < size * size; ++i) image.texels.insert(image.texels.end(), {r, g, b});
  return image;
}

TEST(TextureOutput, AGltfBaseColourTextureIsReadBackAtTheVertices) {
  test::TempDir dir;
  GltfTriangleMesh entry{.name = "quad", .mesh = unit_quad()};
  entry.texcoords = TexcoordMatrix{{0, 1}, {1, 1}, {1, 0}, {0, 0}};
  entry.tangents = TangentMatrix{{1, 0, 0, 1}, {1, 0, 0, 1}, {1, 0, 0, 1}, {1, 0, 0, 1}};
  for (const ImageFormat format : {ImageFormat::png, ImageFormat::jpeg}) {
    entry.base_color_texture = {.bytes = encode_image(flat_image(8, 200, 100, 50), format),
                                .mime_type = std::string(image_mime_type(format))};
    const fs::path path = dir.path() / ("quad_" + std::string(image_format_name(format)) + ".glb");
    write_gltf(path, {.triangle_meshes = {entry}});
    const LoadedMesh loaded = read_mesh(path);
    ASSERT_EQ(loaded.attributes.colors.rows(), 4) << image_format_name(format);
    const int tolerance = format == ImageFormat::png ? 1 : 3;  // JPEG's loss on a flat image
    for (Index v = 0; v < 4; ++v) {
      EXPECT_NEAR(loaded.attributes.colors(v, 0) * 255, 200, tolerance);
      EXPECT_NEAR(loaded.attributes.colors(v, 1) * 255, 100, tolerance);
      EXPECT_NEAR(loaded.attributes.colors(v, 2) * 255, 50, tolerance);
    }
  }
}

TEST(TextureOutput, EveryBaseColourTextureIsKeptWholeWithEachFacesImage) {
  test::TempDir dir;
  GltfScene scene;
  for (const std::uint8_t red : {std::uint8_t{200}, std::uint8_t{20}}) {
    GltfTriangleMesh& entry = scene.triangle_meshes.emplace_back(GltfTriangleMesh{.mesh = unit_quad()});
    entry.texcoords = TexcoordMatrix{{0, 1}, {1, 1}, {1, 0}, {0, 0}};
    entry.base_color_texture = {.bytes = encode_image(flat_image(2, red, 0, 0), ImageFormat::png),
                                .mime_type = "image/png"};
  }
  const fs::path path = dir.path() / "two.glb";
  write_gltf(path, scene);
  const LoadedMesh loaded = read_mesh(path);
  ASSERT_EQ(loaded.mesh.num_faces(), 4);
  ASSERT_EQ(loaded.texture.images.size(), 2u);
  EXPECT_EQ(loaded.texture.images[0].texels[0], 200);
  EXPECT_EQ(loaded.texture.images[1].texels[0], 20);
  EXPECT_EQ(loaded.texture.face_image, (std::vector<std::int32_t>{0, 0, 1, 1}));
  EXPECT_EQ(loaded.texture.corner_uvs.rows(), 12);
  EXPECT_EQ(loaded.texture.corner_uvs.row(3 * 3 + 1), Eigen::RowVector2d(1, 0)) << "face 3's corner 1 is vertex 2";
  // One texture with a factor that is not white: the colours only, no texture kept.
  scene.triangle_meshes.pop_back();
  scene.triangle_meshes[0].colors = ColorMatrix::Constant(4, 3, 0.5F);
  write_gltf(path, scene);
  EXPECT_TRUE(read_mesh(path).texture.empty()) << "COLOR_0 multiplies the texture: baked from the vertex colours";
}

TEST(TextureOutput, TexturesNeedCoordinatesAndTangentsMustBeDirectionsWithASign) {
  GltfTriangleMesh entry{.mesh = unit_quad()};
  entry.base_color_texture = {.bytes = encode_image(flat_image(4, 1, 2, 3), ImageFormat::png),
                              .mime_type = "image/png"};
  EXPECT_NE(test::error_message([&] {
              (void)encode_gltf({.triangle_meshes = {entry}}, GltfContainer::glb);
            }).find("no texture coordinates"),
            std::string::npos);
  entry.texcoords = TexcoordMatrix::Zero(4, 2);
  entry.tangents = TangentMatrix{{1, 0, 0, 1}, {1, 0, 0, 0.5}, {1, 0, 0, 1}, {1, 0, 0, 1}};
  EXPECT_NE(test::error_message([&] {
              (void)encode_gltf({.triangle_meshes = {entry}}, GltfContainer::glb);
            }).find("tangent of vertex 1"),
            std::string::npos);
  entry.tangents.resize(0, 4);
  entry.base_color_texture.mime_type = "image/webp";
  EXPECT_NE(test::error_message([&] {
              (void)encode_gltf({.triangle_meshes = {entry}}, GltfContainer::glb);
            }).find("image/webp"),
            std::string::npos);
}

TEST(TextureOutput, ObjGetsTextureCoordinatesWithVUpAndItsMaterialLibrary) {
  test::TempDir dir;
  const fs::path path = dir.path() / "quad.obj";
  ObjTexturing texturing{.material_library = "quad.mtl", .material = "remesh"};
  texturing.texcoords.resize(4, 2);
  texturing.texcoords << 0, 0.25, 1, 0.25, 1, 1, 0, 1;
  write_obj(path, unit_quad(), {}, texturing);
  const std::string text = test::read_file(path);
  EXPECT_NE(text.find("mtllib quad.mtl\n"), std::string::npos);
  EXPECT_NE(text.find("vt 0 0.75\nvt 1 0.75\nvt 1 0\nvt 0 0\nusemtl remesh\n"), std::string::npos) << text;
  EXPECT_NE(text.find("f 1/1 2/2 3/3\nf 1/1 3/3 4/4\n"), std::string::npos) << text;
  const LoadedMesh back = read_mesh(path);  // geodual's reader takes the vertex indices
  EXPECT_EQ(back.mesh.faces, unit_quad().faces);
  texturing.texcoords.resize(3, 2);
  EXPECT_THROW(write_obj(path, unit_quad(), {}, texturing), Error);
}

// A textured OBJ as scanners export it: quads with vt corners, two materials
// whose map_Kd images lie beside it.
TEST(TextureOutput, ATexturedObjKeepsItsImagesAndEachCornersCoordinates) {
  test::TempDir dir;
  // The library in a folder of its own, its images named from there (one with
  // a space, after options); a material no face uses has no image.
  fs::create_directories(dir.path() / "mats" / "maps");
  io::write_image(dir.path() / "mats" / "maps" / "red one.png", flat_image(4, 200, 10, 10), ImageFormat::png);
  io::write_image(dir.path() / "mats" / "blue.jpg", flat_image(4, 10, 10, 200), ImageFormat::jpeg);
  test::write_file(dir.path() / "mats" / "scan.mtl",
                   "newmtl unused\nKd 1 1 1\n\nnewmtl left\nKd 1 1 1\nmap_Kd -o 0 0 -clamp off maps\\red one.png\n\n"
                   "newmtl right \r\nmap_Kd -s 1 1 1 blue.jpg\r\n");
  test::write_file(dir.path() / "more.mtl", "newmtl other\n");
  const fs::path obj = test::write_file(dir.path() / "scan.obj",
                                        "mtllib mats/scan.mtl more.mtl\nusemtl unused\n"
                                        "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nv 1 1 0\nv 2 1 0\n"
                                        "vt 0 0\nvt 0.5 0\nvt 1 0\nvt 0 1\nvt 0.5 1\nvt 1 1\n"
                                        "usemtl left\nf 1/1 2/2 5/5 4/4\n"
                                        "usemtl right\nf 2/2 3/3 6/6 5/5\n");
  const LoadedMesh loaded = read_mesh(obj);
  ASSERT_EQ(loaded.mesh.num_faces(), 4);
  ASSERT_EQ(loaded.texture.images.size(), 2u);
  EXPECT_EQ(loaded.texture.face_image, (std::vector<std::int32_t>{0, 0, 1, 1}));
  for (Index f = 0; f < 4; ++f) {
    for (int c = 0; c < 3; ++c) {
      const Index v = loaded.mesh.faces(f, c);
      // The corner's coordinates are its vertex's vt: u = x / 2, v = 1 - y (OBJ's v up, glTF's down).
      EXPECT_DOUBLE_EQ(loaded.texture.corner_uvs(3 * f + c, 0), loaded.mesh.vertices(v, 0) / 2);
      EXPECT_DOUBLE_EQ(loaded.texture.corner_uvs(3 * f + c, 1), 1 - loaded.mesh.vertices(v, 1));
    }
  }
  ASSERT_EQ(loaded.attributes.colors.rows(), 6) << "colours sampled from the images where the vertices have none";
  EXPECT_NEAR(loaded.attributes.colors(0, 0) * 255, 200, 1);
  EXPECT_NEAR(loaded.attributes.colors(2, 2) * 255, 200, 4);  // from the JPEG

  // An image that is not there: the mesh is read, the texture left out with a note.
  fs::remove(dir.path() / "mats" / "blue.jpg");
  const LoadedMesh without = read_mesh(obj);
  EXPECT_TRUE(without.texture.empty());
  EXPECT_EQ(without.mesh.num_faces(), 4);
  EXPECT_TRUE(std::any_of(without.info.notes.begin(), without.info.notes.end(),
                          [](const std::string& note) { return note.find("texture ignored") == 0; }));
}

TEST(TextureOutput, PlyNamesItsTextureFileInAComment) {
  test::TempDir dir;
  const fs::path path = dir.path() / "quad.ply";
  write_ply(path, unit_quad(), {}, "quad_basecolor.png");
  const std::string text = test::read_file(path);
  EXPECT_EQ(text.find("ply\nformat binary_little_endian 1.0\ncomment written by geodual\ncomment TextureFile "
                      "quad_basecolor.png\nelement vertex 4\n"),
            0u);
  EXPECT_EQ(read_mesh(path).mesh.faces, unit_quad().faces);
  EXPECT_THROW(write_ply(path, unit_quad(), {}, "two\nlines.png"), Error);
}

TEST(TextureOutput, ImagesAreRefusedWhenTheirTexelsDoNotMatchTheirSize) {
  TextureImage image = flat_image(4, 1, 2, 3);
  EXPECT_EQ(encode_image(image, ImageFormat::png), encode_image(image, ImageFormat::png)) << "deterministic";
  image.texels.pop_back();
  EXPECT_THROW((void)encode_image(image, ImageFormat::png), Error);
  image = flat_image(4, 1, 2, 3);
  image.channels = 2;
  EXPECT_THROW((void)encode_image(image, ImageFormat::jpeg), Error);
}

}  // namespace
}  // namespace geodual::io
