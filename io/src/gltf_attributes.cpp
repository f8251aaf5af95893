#include "gltf_attributes.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <utility>

namespace geodual::io::detail::gltf {
namespace {

// [0, 1], with NaN read as 0.
float clamp01(double value) { return value >= 0.0 ? static_cast<float>(std::min(value, 1.0)) : 0.0f; }

std::string joined(const std::vector<std::string>& parts, std::string_view separator) {
  std::string text;
  for (const std::string& part : parts) text += (text.empty() ? "" : std::string(separator)) + part;
  return text;
}

std::string counted(std::size_t n, std::string_view one, std::string_view many) {
  return std::to_string(n) + " " + std::string(n == 1 ? one : many);
}

// How a scalar attribute's values are kept: integer types as they are, everything else as float32.
ValueType scalar_type(const AccessorView& view) {
  if (view.normalized) return ValueType::float32;
  switch (view.component_type) {
    case ComponentType::byte: return ValueType::int8;
    case ComponentType::unsigned_byte: return ValueType::uint8;
    case ComponentType::short_: return ValueType::int16;
    case ComponentType::unsigned_short: return ValueType::uint16;
    case ComponentType::unsigned_int: return ValueType::uint32;
    case ComponentType::float_: return ValueType::float32;
  }
  return ValueType::float32;
}

// The matrix that turns normals under the linear map m: m's inverse transpose,
// up to a positive factor (the cofactor matrix times the determinant's sign),
// which is defined even where m is singular.
Eigen::Matrix3d normal_matrix(const Eigen::Matrix3d& m) {
  Eigen::Matrix3d cofactor;
  cofactor.col(0) = m.col(1).cross(m.col(2));
  cofactor.col(1) = m.col(2).cross(m.col(0));
  cofactor.col(2) = m.col(0).cross(m.col(1));
  return m.determinant() < 0 ? Eigen::Matrix3d(-cofactor) : cofactor;
}

}  // namespace

AttributeReader::AttributeReader(const Json& root, BufferStore& buffers, TextureStore& textures, bool allow_quantized,
                                 std::string where)
    : root_(root),
      buffers_(buffers),
      textures_(textures),
      allow_quantized_(allow_quantized),
      where_(std::move(where)) {}

AccessorView AttributeReader::view_attribute(std::size_t accessor, std::initializer_list<AccessorShape> shapes,
                                             std::size_t vertex_count, const std::string& where) {
  AccessorView view = view_accessor(root_, buffers_, accessor, shapes, where);
  if (view.count != vertex_count) {
    fail(view.where, "has " + std::to_string(view.count) + " elements, but the primitive's POSITION has " +
                         std::to_string(vertex_count) + " (all attributes of a primitive have one per vertex)");
  }
  if (view.component_type == ComponentType::float_ && view.normalized) {
    fail(view.where, "a FLOAT accessor cannot be normalized");
  }
  return view;
}

PrimitiveAttributes AttributeReader::plan(const Json& primitive, const Json& attributes, std::size_t vertex_count,
                                          const std::string& where) {
  PrimitiveAttributes plan;
  const std::size_t accessor_count = array_member(root_, "accessors", where).size();
  for (const auto& [name, value] : attributes.items()) {
    if (name == "POSITION") continue;
    seen_attributes_.insert(name);
    const bool color = name == "COLOR_0";
    const bool normal = name == "NORMAL";
    const bool scalar = name.size() > 1 && name[0] == '_';
    if (!color && !normal && !scalar) continue;
    const std::size_t accessor = index_value(value, accessor_count, "accessor", where + ": " + name);
    const std::string attribute_where = where + ": " + name;
    if (color) {
      plan.color = view_attribute(accessor, {AccessorShape::vec3, AccessorShape::vec4}, vertex_count, attribute_where);
      const ComponentType type = plan.color->component_type;
      if (type != ComponentType::float_ &&
          !((type == ComponentType::unsigned_byte || type == ComponentType::unsigned_short) &&
            plan.color->normalized)) {
        fail(plan.color->where, "COLOR_0 has componentType " + std::string(component_type_name(type)) +
                                    (plan.color->normalized ? "" : " (not normalized)") +
                                    "; glTF allows FLOAT, or normalized UNSIGNED_BYTE or UNSIGNED_SHORT");
      }
    } else if (normal) {
      plan.normal = view_attribute(accessor, {AccessorShape::vec3}, vertex_count, attribute_where);
      const ComponentType type = plan.normal->component_type;
      const bool quantized = (type == ComponentType::byte || type == ComponentType::short_) && plan.normal->normalized;
      if (type != ComponentType::float_ && !(quantized && allow_quantized_)) {
        fail(plan.normal->where, "NORMAL has componentType " + std::string(component_type_name(type)) +
                                     "; glTF requires FLOAT (normalized BYTE or SHORT with KHR_mesh_quantization)");
      }
    } else {
      if (accessor_type(root_, accessor) != "SCALAR") continue;  // listed as ignored
      plan.scalars.emplace(name.substr(1),
                           view_attribute(accessor, {AccessorShape::scalar}, vertex_count, attribute_where));
    }
    used_attributes_.insert(name);
    plan.sources[name] = accessor;
  }
  plan_material(primitive, attributes, vertex_count, plan, where);
  return plan;
}

void AttributeReader::plan_material(const Json& primitive, const Json& attributes, std::size_t vertex_count,
                                    PrimitiveAttributes& plan, const std::string& where) {
  const Json& materials = array_member(root_, "materials", where);
  const std::optional<std::size_t> index = optional_index(primitive, "material", materials.size(), "material", where);
  if (!index) return;
  plan.sources["material"] = *index;
  const Json& material = materials[*index];
  const std::string material_where = where + ": " + describe("material", *index, material);
  if (!material.is_object()) fail(material_where, "must be a JSON object");
  const Json* pbr = optional_object(material, "pbrMetallicRoughness", material_where);
  if (pbr == nullptr) return;
  const std::string pbr_where = material_where + ": pbrMetallicRoughness";
  if (const auto factor = optional_numbers<4>(*pbr, "baseColorFactor", pbr_where)) plan.base_color_factor = *factor;

  const Json* texture_info = optional_object(*pbr, "baseColorTexture", pbr_where);
  if (texture_info == nullptr) return;
  const std::string info_where = pbr_where + ": baseColorTexture";
  const std::size_t texture_count = array_member(root_, "textures", info_where).size();
  const std::size_t texture = required_index(*texture_info, "index", texture_count, "texture", info_where);
  plan.texcoord_set = optional_uint(*texture_info, "texCoord", info_where).value_or(0);
  if (const Json* extensions = optional_object(*texture_info, "extensions", info_where);
      extensions != nullptr && find_member(*extensions, "KHR_texture_transform") != nullptr) {
    transformed_texture_materials_.insert(*index);
    plan.texture_transformed = true;
  }
  const std::optional<TextureStore::Texture> found = textures_.texture(texture, info_where);
  if (!found) {
    textures_without_source_.insert(texture);
    return;
  }
  const std::string texcoord_name = "TEXCOORD_" + std::to_string(plan.texcoord_set);
  const Json* texcoord_value = find_member(attributes, texcoord_name);
  if (texcoord_value == nullptr) {
    ++primitives_without_texcoord_;
    return;
  }
  const std::string texcoord_where = where + ": " + texcoord_name;
  const std::size_t accessor =
      index_value(*texcoord_value, array_member(root_, "accessors", where).size(), "accessor", texcoord_where);
  plan.texcoord = view_attribute(accessor, {AccessorShape::vec2}, vertex_count, texcoord_where);
  const ComponentType type = plan.texcoord->component_type;
  const bool normalized_unsigned =
      (type == ComponentType::unsigned_byte || type == ComponentType::unsigned_short) && plan.texcoord->normalized;
  const bool quantized = type != ComponentType::unsigned_int && allow_quantized_;
  if (type != ComponentType::float_ && !normalized_unsigned && !quantized) {
    fail(plan.texcoord->where, texcoord_name + " has componentType " + std::string(component_type_name(type)) +
                                   "; glTF allows FLOAT, or normalized UNSIGNED_BYTE or UNSIGNED_SHORT");
  }
  plan.texture = found;
  used_attributes_.insert(texcoord_name);
  plan.sources[texcoord_name] = accessor;
}

void AttributeReader::choose(const std::vector<const PrimitiveAttributes*>& primitives, std::size_t total_vertices) {
  const std::size_t n = primitives.size();
  const std::array<double, 4> white{1, 1, 1, 1};
  bool any_color = false;
  bool any_factor = false;
  bool any_float = false;
  bool any_short = false;
  bool any_byte = false;
  std::set<std::size_t> texcoord_sets;
  std::size_t with_normal = 0;
  std::map<std::string, std::size_t> with_scalar;
  std::map<std::string, std::set<ValueType>> scalar_types;
  for (const PrimitiveAttributes* p : primitives) {
    if (p->color) {
      any_color = true;
      any_float = any_float || p->color->component_type == ComponentType::float_;
      any_short = any_short || p->color->component_type == ComponentType::unsigned_short;
      any_byte = any_byte || p->color->component_type == ComponentType::unsigned_byte;
    }
    if (p->base_color_factor != white) any_factor = true;
    if (p->texture) {
      any_byte = true;
      texcoord_sets.insert(p->texcoord_set);
    }
    if (p->normal) ++with_normal;
    for (const auto& [name, view] : p->scalars) {
      ++with_scalar[name];
      scalar_types[name].insert(scalar_type(view));
    }
  }

  read_colors_ = any_color || any_factor || !texcoord_sets.empty();
  if (read_colors_) {
    color_type_ = any_float   ? ValueType::float32
                  : any_short ? ValueType::uint16
                  : any_byte  ? ValueType::uint8
                              : ValueType::float32;
    std::vector<std::string> sources;
    if (any_color) sources.emplace_back("COLOR_0");
    if (any_factor) sources.emplace_back("baseColorFactor");
    if (!texcoord_sets.empty()) {
      std::vector<std::string> sets;
      for (const std::size_t set : texcoord_sets) sets.push_back("TEXCOORD_" + std::to_string(set));
      sources.push_back("baseColorTexture sampled at " + joined(sets, " and "));
    }
    notes_.push_back("vertex colours: " + joined(sources, " x ") +
                     " (the glTF base colour, multiplied in linear space, stored sRGB-encoded)");
    colors_.reserve(4 * total_vertices);
  }

  // The textures kept whole: every primitive's base colour an image alone.
  bool textures_alone = n > 0;
  bool sampled_as_baked = true;  // REPEAT both ways, no transform: as the baker samples
  for (const PrimitiveAttributes* p : primitives) {
    textures_alone = textures_alone && p->texture && p->texcoord && !p->color && p->base_color_factor == white;
    sampled_as_baked = sampled_as_baked && p->texture && !p->texture_transformed &&
                       p->texture->sampler.wrap_s == WrapMode::repeat && p->texture->sampler.wrap_t == WrapMode::repeat;
  }
  if (textures_alone && !sampled_as_baked) {
    textures_alone = false;
    notes_.emplace_back(
        "base colour textures not kept for baking: a sampler clamps or mirrors, or "
        "KHR_texture_transform moves them (the vertex colours are baked instead)");
  }
  if (textures_alone) {
    for (const PrimitiveAttributes* p : primitives) {
      if (std::find(kept_images_.begin(), kept_images_.end(), p->texture->image) == kept_images_.end()) {
        kept_images_.push_back(p->texture->image);
      }
    }
    texcoords_.reserve(2 * total_vertices);
    notes_.push_back(counted(kept_images_.size(), "base colour texture", "base colour textures") +
                     " kept whole for baking, with the TEXCOORD at every vertex");
  }

  read_normals_ = n > 0 && with_normal == n;
  if (read_normals_) {
    notes_.emplace_back("vertex normals from NORMAL");
    normals_.reserve(3 * total_vertices);
  } else if (with_normal > 0) {
    notes_.push_back("NORMAL missing in " + std::to_string(n - with_normal) + " of " +
                     counted(n, "triangle primitive", "triangle primitives") + ": normals not read");
  }

  for (const auto& [name, count] : with_scalar) {
    if (count < n) {
      notes_.push_back("vertex attribute '_" + name + "' missing in " + std::to_string(n - count) + " of " +
                       counted(n, "triangle primitive", "triangle primitives") + ": not read");
      continue;
    }
    const std::set<ValueType>& types = scalar_types.at(name);
    OutputScalar scalar;
    scalar.name = name;
    scalar.type = types.size() == 1 ? *types.begin() : ValueType::float64;
    scalar.values.reserve(total_vertices);
    notes_.push_back("vertex attribute '_" + name + "' read as scalar '" + name + "'");
    scalars_.push_back(std::move(scalar));
  }
}

void AttributeReader::append(const PrimitiveAttributes& primitive, std::size_t count, const MeshInstance& instance) {
  if (read_colors_) append_colors(primitive, count);
  if (!kept_images_.empty()) {
    for_each_element(*primitive.texcoord, [&](std::size_t, const double* uv) {
      texcoords_.insert(texcoords_.end(), {uv[0], uv[1]});
    });
  }
  if (read_normals_) append_normals(primitive, count, instance);
  for (OutputScalar& scalar : scalars_) {
    for_each_element(primitive.scalars.at(scalar.name), [&](std::size_t, const double* value) {
      scalar.finite = scalar.finite && std::isfinite(value[0]);
      scalar.values.push_back(value[0]);
    });
  }
}

void AttributeReader::append_colors(const PrimitiveAttributes& primitive, std::size_t count) {
  const std::size_t first = colors_.size();
  colors_.resize(first + 4 * count);
  float* const rows = colors_.data() + first;
  std::array<float, 4> factor{};
  for (std::size_t k = 0; k < 4; ++k) factor[k] = clamp01(primitive.base_color_factor[k]);
  for (std::size_t v = 0; v < count; ++v) std::copy(factor.begin(), factor.end(), rows + 4 * v);

  if (primitive.color) {
    const std::size_t channels = primitive.color->components;  // 3 or 4; a missing alpha is 1
    for_each_element(*primitive.color, [&](std::size_t v, const double* color) {
      for (std::size_t k = 0; k < channels; ++k) rows[4 * v + k] *= clamp01(color[k]);
    });
  }
  if (primitive.texture && primitive.texcoord) {
    const DecodedImage& image = textures_.image(primitive.texture->image);
    const TextureSampler& sampler = primitive.texture->sampler;
    for_each_element(*primitive.texcoord, [&](std::size_t v, const double* uv) {
      const std::array<float, 4> texel = sample_texture(image, sampler, uv[0], uv[1]);
      for (std::size_t k = 0; k < 4; ++k) rows[4 * v + k] *= texel[k];
    });
  }
  for (std::size_t v = 0; v < count; ++v) {
    for (std::size_t k = 0; k < 3; ++k) rows[4 * v + k] = srgb_from_linear(rows[4 * v + k]);
  }
}

void AttributeReader::append_normals(const PrimitiveAttributes& primitive, std::size_t count,
                                     const MeshInstance& instance) {
  const Eigen::Matrix3d turn = normal_matrix(instance.world.linear());
  const std::size_t first = normals_.size();
  normals_.resize(first + 3 * count);
  for_each_element(*primitive.normal, [&](std::size_t v, const double* normal) {
    Eigen::Map<Eigen::Vector3d> out(normals_.data() + first + 3 * v);
    out = Eigen::Vector3d(normal[0], normal[1], normal[2]);
    if (!instance.identity) out = turn * out;
    const double length = out.norm();
    if (length > 0.0 && std::isfinite(length)) out /= length;
    normals_finite_ = normals_finite_ && out.allFinite();
  });
}

std::int32_t AttributeReader::kept_image(const PrimitiveAttributes& primitive) const {
  if (kept_images_.empty() || !primitive.texture) return -1;
  const auto at = std::find(kept_images_.begin(), kept_images_.end(), primitive.texture->image);
  return at == kept_images_.end() ? -1 : static_cast<std::int32_t>(at - kept_images_.begin());
}

SurfaceTexture AttributeReader::take_texture(const FaceMatrix& faces, std::vector<std::int32_t> face_image) {
  SurfaceTexture texture;
  if (kept_images_.empty()) return texture;
  for (const std::size_t index : kept_images_) texture.images.push_back(texture_image(textures_.image(index)));
  texture.corner_uvs.resize(3 * faces.rows(), 2);
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    for (int c = 0; c < 3; ++c) {
      const auto v = static_cast<std::size_t>(faces(f, c));
      texture.corner_uvs.row(3 * f + c) << texcoords_[2 * v], texcoords_[2 * v + 1];
    }
  }
  if (kept_images_.size() > 1) texture.face_image = std::move(face_image);
  return texture;
}

VertexAttributes AttributeReader::take() {
  VertexAttributes result;
  if (read_colors_) {
    const auto rows = static_cast<Eigen::Index>(colors_.size() / 4);
    bool alpha = false;
    for (std::size_t v = 3; v < colors_.size(); v += 4) alpha = alpha || colors_[v] < 1.0f;
    const Eigen::Map<const Eigen::Matrix<float, Eigen::Dynamic, 4, Eigen::RowMajor>> rgba(colors_.data(), rows, 4);
    result.colors = alpha ? ColorMatrix(rgba) : ColorMatrix(rgba.leftCols<3>());
    result.color_type = color_type_;
    if (alpha) notes_.emplace_back("vertex colours have an alpha column (some alpha is below 1)");
    colors_ = {};
  }
  if (read_normals_) {
    if (normals_finite_) {
      result.normals =
          Eigen::Map<const VertexMatrix>(normals_.data(), static_cast<Eigen::Index>(normals_.size() / 3), 3);
      result.normal_type = ValueType::float32;
    } else {
      notes_.emplace_back("NORMAL holds non-finite values: normals dropped");
    }
    normals_ = {};
  }
  for (OutputScalar& scalar : scalars_) {
    if (!scalar.finite) {
      notes_.push_back("vertex attribute '_" + scalar.name + "' holds non-finite values: dropped");
      continue;
    }
    result.scalars.push_back({.name = std::move(scalar.name), .type = scalar.type, .values = std::move(scalar.values)});
  }
  scalars_.clear();
  return result;
}

std::vector<std::string> AttributeReader::notes() const {
  std::vector<std::string> notes = notes_;
  for (const std::size_t texture : textures_without_source_) {
    notes.push_back("texture " + std::to_string(texture) +
                    " has no PNG or JPEG source (only an extension's image format, e.g. KTX2 or WebP): its colours "
                    "ignored");
  }
  if (!transformed_texture_materials_.empty()) {
    notes.push_back("KHR_texture_transform ignored (" +
                    counted(transformed_texture_materials_.size(), "material", "materials") +
                    "): textures sampled at the untransformed TEXCOORD");
  }
  if (primitives_without_texcoord_ > 0) {
    notes.push_back(counted(primitives_without_texcoord_, "primitive lacks", "primitives lack") +
                    " the TEXCOORD its baseColorTexture needs: texture ignored there");
  }
  std::vector<std::string> ignored;
  for (const std::string& name : seen_attributes_) {
    if (!used_attributes_.contains(name)) ignored.push_back(name);
  }
  if (!ignored.empty()) notes.push_back("vertex attributes ignored: " + joined(ignored, ", "));
  return notes;
}

}  // namespace geodual::io::detail::gltf
