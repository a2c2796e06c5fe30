// scene.h — the scene-file data model (format v1, see docs/scene-format.md).
//
// One format for every lab: a lab reads the sections it teaches and ignores
// the rest (lab1 ignores "lights"). The loader validates everything up front so
// a lab never sees a half-valid scene: any problem throws SceneError whose
// message is one line "FILE: JSON.PATH: reason".
#pragma once

#include <glm/glm.hpp>

#include <map>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

namespace lab {

struct CameraDesc {
    enum class Mode { LookAt, Transform };
    Mode mode = Mode::LookAt;
    glm::vec3 position{0.0f, 2.0f, 6.0f};
    glm::vec3 target{0.0f, 0.0f, 0.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float yaw_deg = 0.0f;
    float pitch_deg = 0.0f;
    float roll_deg = 0.0f;
    float fov_y_deg = 60.0f;
    float near_plane = 0.01f;
    float far_plane = 100.0f;
};

struct AmbientDesc {
    glm::vec3 color{1.0f};
    float intensity = 0.1f;
};

// Lab 4: one light's shadow map (docs/scene-format.md, "shadow"). The defaults are the ones
// lab4_shadows/README.md measures as the best time against error.
struct ShadowDesc {
    enum class Filter { Nearest, Bilinear };  // manual depth compare | comparison sampler (2×2 per tap)
    int resolution = 2048;       // texels per side (per cube face for a point light)
    int pcf = 1;                 // an N×N kernel, N odd; 1 = a single tap
    Filter filter = Filter::Nearest;
    float bias = 1.0f;           // constant depth bias of the shadow pass (vkCmdSetDepthBias)
    float slope_bias = 1.5f;     // slope-scaled depth bias of the shadow pass
    float normal_offset = 1.0f;  // lookup point moved along the normal, in shadow-map texels
    bool fit_to_view = false;    // draw only as many texels as the picture can show (≤ resolution per side)
};

struct LightDesc {
    enum class Type { Directional, Point, Spot };
    Type type = Type::Directional;
    glm::vec3 position{0.0f};
    glm::vec3 direction{0.0f, -1.0f, 0.0f};  // the way the light travels
    glm::vec3 color{1.0f};
    float intensity = 1.0f;
    glm::vec3 attenuation{1.0f, 0.0f, 0.0f};  // [constant, linear, quadratic]
    float inner_deg = 12.5f;
    float outer_deg = 17.5f;
    bool cast_shadows = false;  // lab 4
    ShadowDesc shadow;
};

// A light type's name in the scene format ("directional", "point", "spot"): what panels and pass
// names show, and what read_scene() accepts.
const char* light_type_name(LightDesc::Type type);

// Lab 3: how a texture is read (docs/scene-format.md, "sampler"). The default is the seed's:
// bilinear, linear between mip levels, anisotropy 16 by the sampler, repeat.
struct SamplerDesc {
    enum class Filter { Nearest, Linear };
    enum class Mipmaps { None, Nearest, Linear };
    enum class Wrap { Repeat, Clamp, Mirror };
    // Who filters anisotropically: the VkSampler (maxAnisotropy) or the fragment shader, with up to
    // `anisotropy` probes along the footprint's major axis, each read as `mipmaps` says (linear:
    // trilinear; nearest: bilinear on the nearest level). Not without mipmaps. Auto: the lab picks
    // one for its device (lab 3's sampler_cache.h, choose_anisotropic) before anything reads this.
    enum class Anisotropic { Sampler, Probes, Auto };
    Filter filter = Filter::Linear;
    Mipmaps mipmaps = Mipmaps::Linear;
    int anisotropy = 16;  // 1 = off; with probes: the most probes per lookup
    Wrap wrap = Wrap::Repeat;
    Anisotropic anisotropic = Anisotropic::Sampler;
    // The shader's probe maximum (0: a plain lookup). The UI may pair probes with "mipmaps": "none"
    // (the loader may not): that falls back to the plain lookup.
    int probes() const {
        return anisotropic == Anisotropic::Probes && mipmaps != Mipmaps::None && anisotropy > 1 ? anisotropy : 0;
    }
    bool operator<(const SamplerDesc& o) const {
        return std::tie(filter, mipmaps, anisotropy, wrap, anisotropic) <
               std::tie(o.filter, o.mipmaps, o.anisotropy, o.wrap, o.anisotropic);
    }
    bool operator==(const SamplerDesc& o) const { return !(*this < o) && !(o < *this); }
};

// Lab 3: the seed's distorted-UV multi-sampling (a wobbled lookup blended with rescaled ones), every
// number a key (defaults = the seed's); what each one does: docs/scene-format.md, "distortion".
struct DistortionDesc {
    glm::vec2 amplitude{0.02f, 0.015f};
    glm::vec2 frequency{10.0f, 8.0f};
    glm::vec2 position_frequency{2.0f, 1.5f};
    glm::vec2 scales{2.0f, 0.5f};
    glm::vec2 weights{0.3f, 0.2f};
};

struct MaterialDesc {
    glm::vec3 albedo{0.8f};
    glm::vec3 specular{0.0f};
    float shininess = 32.0f;
    glm::vec3 emissive{0.0f};
    // Lab 2 lighting models (docs/lighting.md): Oren-Nayar sigma and Cook-Torrance roughness,
    // Cook-Torrance reflectance at normal incidence, Ward's two roughnesses, Minnaert's exponent.
    float roughness = 0.5f;
    glm::vec3 f0{0.04f};
    float roughness_x = 0.15f;  // Ward: along the mesh tangent (+u)
    float roughness_y = 0.45f;  // Ward: along the bitangent (+v)
    float minnaert_k = 0.8f;
    // Lab 3 texture maps: "" = none, "procedural:NAME", or an absolute image path (resolved
    // against the scene file, or the .mtl file for map_Kd / map_Ks / map_Ke).
    std::string albedo_map;
    std::string specular_map;
    std::string emissive_map;
    float emissive_strength = 1.0f;  // how strongly the emissive map E glows (docs/scene-format.md)
    float opacity = 1.0f;            // lab 4: < 1 is translucent (blended α, 1 − α; shadows let 1 − α through)
    glm::vec2 uv_scale{1.0f};        // the map's repeats across the mesh's uv (docs/scene-format.md)
    glm::vec2 uv_offset{0.0f};
    SamplerDesc sampler;
    bool distorted = false;  // "sampling": "distorted" (albedo map only) instead of "single"
    DistortionDesc distortion;
    bool has_maps() const { return !albedo_map.empty() || !specular_map.empty() || !emissive_map.empty(); }
};

// The procedural texture names a map may use after "procedural:" (docs/scene-format.md).
const std::vector<std::string>& procedural_texture_names();
// False for "procedural:NAME" with a NAME not in that list (the scene loader's error); true for
// anything else (an image path, checked when it is loaded).
bool known_procedural_or_path(const std::string& map);

// Lab 2: which shading and lighting model a scene uses (docs/lighting.md).
struct LightingDesc {
    enum class Model { Lambert, Phong, BlinnPhong, Toon, OrenNayar, Minnaert, CookTorrance, Ward };
    enum class Shading { Flat, Gouraud, Phong };
    enum class SpotFalloff { Smooth, Edge };      // inner/outer ramp, or 1 - (1 - cos b)/(1 - cos a)
    enum class Distribution { GGX, Beckmann };    // Cook-Torrance microfacet distribution
    enum class NanCheck { Off, On, SelfTest };    // paint NaN/Inf pixels magenta (tests)
    Model model = Model::BlinnPhong;
    Shading shading = Shading::Phong;
    SpotFalloff spot_falloff = SpotFalloff::Smooth;
    Distribution distribution = Distribution::GGX;
    int toon_bands = 4;
    bool markers = false;  // draw light markers (the UI can toggle them)
    NanCheck nan_check = NanCheck::Off;
};

struct ObjectDesc {
    std::string mesh;       // "plane" | "cube" | "sphere" | path as written in the file
    std::string mesh_path;  // for file meshes: absolute path (resolved against the scene file)
    std::string material;   // key into Scene::materials (validated to exist); for a model
                            // without "material" the loader fills in its .mtl materials
    // File meshes split by .mtl material: only the triangles of .mtl material
    // number obj_material (−1: those without one); kAllTriangles: the whole model.
    static constexpr int kAllTriangles = -2;
    int obj_material = kAllTriangles;
    glm::vec3 position{0.0f};
    glm::vec3 rotation_deg{0.0f};  // [rx, ry, rz]
    glm::vec3 scale{1.0f};
    // Mesh options (see docs/meshes.md); 0 = the primitive's default tessellation.
    int segments = 0;
    int rings = 0;
    float crease_deg = 60.0f;  // file meshes without normals: split vertices at sharper edges
    bool normalize = false;    // file meshes: fit into a unit box centered at the origin
    bool cast_shadows = true;  // lab 4: drawn into the shadow maps of shadow-casting lights
};

struct Scene {
    std::string file;  // the file it was loaded from ("" when parsed from a string)
    CameraDesc camera;
    glm::vec3 background{0.05f, 0.05f, 0.08f};
    AmbientDesc ambient;
    LightingDesc lighting;
    std::vector<LightDesc> lights;
    std::map<std::string, MaterialDesc> materials;
    std::vector<ObjectDesc> objects;
};

// Thrown for every bad input. what() is the complete one-line message.
class SceneError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// Reads and validates a scene file. Throws SceneError.
Scene load_scene(const std::string& file);

// Parses scene JSON text. `file_label` is used in messages, `base_dir` to
// resolve relative mesh paths. Throws SceneError.
Scene parse_scene(const std::string& json_text, const std::string& file_label,
                  const std::string& base_dir);

// M = T(position) · Rz(rz) · Ry(ry) · Rx(rx) · S(scale)
glm::mat4 model_matrix(const ObjectDesc& object);

// The built-in mesh names the loader accepts in "mesh" (plane, cube, sphere,
// ...; see docs/meshes.md). make_mesh must build every one of them.
const std::vector<std::string>& primitive_mesh_names();

}  // namespace lab
