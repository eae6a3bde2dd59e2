// SPDX-License-Identifier: Apache-2.0
// shadecore — scene files for `shadecore render` (docs/scenes.md).
//
// A scene is OpenGL 1.x fixed-function state written as JSON: a gluLookAt/gluPerspective camera, the
// light model (glLightModel), up to 8 lights (glLight), named materials (glMaterial plus which specular
// unit of the core shades them), and objects (tessellated sphere, plane, torus, OBJ mesh) with a
// transform (glTranslate · glRotate · glScale), a material and a shading mode (flat / Gouraud / Phong).
//
// Parsing is strict: malformed JSON (with line and column), unknown or duplicate keys, wrong types and
// out-of-range values, a missing or malformed OBJ file and degenerate faces are all a SceneError whose
// message is one line "FILE: JSON.PATH: what".
// Host software: nothing here is hardware.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "shadecore/light.hpp"
#include "shadecore/units/coef.hpp"
#include "shadecore/units/cs16.hpp"
#include "shadecore/unit.hpp"

namespace shadecore::scene {

class SceneError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

using Vec3 = std::array<double, 3>;
using Vec4 = std::array<double, 4>;

enum class Shading { Flat, Gouraud, Phong };
const char* to_string(Shading s);
Shading parse_shading(const std::string& s);  // throws std::invalid_argument

// How flat shading picks the one colour of a polygon (the scene's top-level "flat_rule"):
//   Centroid         the face lit once at its centroid with its geometric (Newell) normal (the default);
//   ProvokingVertex  OpenGL's GL_FLAT: each triangle (v0, vk, vk+1) of the face's fan takes the colour of its
//                    provoking vertex, GL_TRIANGLES' last vertex vk+1, lit with that vertex's normal and position.
enum class FlatRule { Centroid, ProvokingVertex };
const char* to_string(FlatRule r);
FlatRule parse_flat_rule(const std::string& s);  // throws std::invalid_argument

// glColorMaterial(GL_FRONT_AND_BACK, mode) with GL_COLOR_MATERIAL enabled, per object (the scene's
// objects[i].color_material); nullopt: `none`, GL_COLOR_MATERIAL disabled.
const char* to_string(std::optional<ColourMaterial> m);
std::optional<ColourMaterial> parse_colour_material(const std::string& s);  // throws std::invalid_argument

struct Camera {            // gluLookAt(eye, center, up) + gluPerspective(fovy, aspect = width/height, near, far)
  Vec3 eye{0, 0, 5}, center{0, 0, 0}, up{0, 1, 0};
  double fovy = 45.0;      // degrees, (0, 180)
  double near = 1.0, far = 100.0;
};

struct Light {             // glLightfv(GL_LIGHTi, ...), specified with the view matrix on the modelview stack
  Vec4 position{0, 0, 1, 0};  // world coordinates; w = 0 directional (towards the light), else point
  Vec3 ambient{0, 0, 0}, diffuse{1, 1, 1}, specular{1, 1, 1};
  double kc = 1, kl = 0, kq = 0;  // GL_CONSTANT/LINEAR/QUADRATIC_ATTENUATION
  Vec3 spot_direction{0, 0, -1};  // GL_SPOT_DIRECTION, world coordinates (transformed like position, w = 0)
  double spot_cutoff = 180;       // GL_SPOT_CUTOFF, degrees: 0..90, or 180 (no cone)
  int spot_exponent = 0;          // GL_SPOT_EXPONENT, 0..128
  [[nodiscard]] bool is_spot() const { return position[3] != 0.0 && spot_cutoff != 180.0; }
};

struct Normalization {     // optional energy normalisation of the specular term (rtl/sc_energy.v)
  Model model = Model::Blinn;
  CoefKind kind = CoefKind::Fitted;
};

// A material's "back" object: glMaterialfv(GL_BACK, ...), used for back-facing polygons under
// GL_LIGHT_MODEL_TWO_SIDE (light_model.two_side). The back face shares the front's specular unit, cut-off and
// normalisation; its shininess may differ (the core holds one unit material: the renderer writes the back's between
// the front-facing and the back-facing fragments, docs/scenes.md).
struct BackMaterial {
  Vec3 emission{0, 0, 0}, ambient{0.2, 0.2, 0.2}, diffuse{0.8, 0.8, 0.8}, specular{0, 0, 0};
  int shininess = 16;
};

struct Material {          // glMaterialfv(GL_FRONT, ...) (GL_FRONT_AND_BACK without "back")
  std::string name;
  Vec3 emission{0, 0, 0}, ambient{0.2, 0.2, 0.2}, diffuse{0.8, 0.8, 0.8}, specular{0, 0, 0};
  int shininess = 16;      // n, 0..1024 (below 16: the low-shininess chain, docs/lighting.md §3.5); GL's default is 0
  VariantId unit = VariantId::cs16;
  Cutoff cutoff = Cutoff::ThetaCr;
  std::optional<Normalization> normalization;
  std::optional<BackMaterial> back;  // "back": GL_BACK's colours; nullopt: the front's (GL_FRONT_AND_BACK)
  [[nodiscard]] bool has_specular() const { return specular[0] > 0 || specular[1] > 0 || specular[2] > 0; }
  // The back face's colours: `back` if given, else the front's.
  [[nodiscard]] BackMaterial back_or_front() const {
    return back ? *back : BackMaterial{emission, ambient, diffuse, specular, shininess};
  }
  // This material with the back face's colours and shininess in place of the front's (unit, cut-off, normalisation
  // kept).
  [[nodiscard]] Material back_face() const {
    Material m = *this;
    const BackMaterial b = back_or_front();
    m.emission = b.emission, m.ambient = b.ambient, m.diffuse = b.diffuse, m.specular = b.specular;
    m.shininess = b.shininess;
    m.back.reset();
    return m;
  }
};

struct Rotation {          // glRotated(angle, x, y, z)
  double angle = 0;
  Vec3 axis{0, 0, 1};
};
struct Transform {         // modelview = view · T · R1 · R2 · … · S (the order of the GL calls)
  Vec3 translate{0, 0, 0};
  std::vector<Rotation> rotate;
  Vec3 scale{1, 1, 1};
};

enum class ObjectType { Sphere, Plane, Torus, Mesh };

struct Object {
  std::string name;        // for messages and the JSON report ("objects[i]" if not given)
  ObjectType type = ObjectType::Sphere;
  // sphere (gluSphere: poles on ±z)
  double radius = 1.0;
  int slices = 16, stacks = 8;
  // plane (the xy square [-w/2, w/2] × [-h/2, h/2], normal +z)
  double width = 2.0, height = 2.0;
  int subdivisions = 1;
  // torus (glutSolidTorus: around the z axis)
  double inner_radius = 0.25, outer_radius = 1.0;
  int sides = 12, rings = 24;
  // mesh (OBJ through tinyobjloader)
  std::string file;        // as written in the scene
  std::string file_path;   // resolved against the scene's directory
  Transform transform;
  int material = 0;        // index into Scene::materials
  Shading shading = Shading::Phong;
  // GL_COLOR_MATERIAL: the material colour(s) the object's colours replace (nullopt: none), and GL's current colour
  // (glColor3f) where the mesh has no per-vertex colours (built-in primitives, OBJ files without `v x y z r g b`)
  std::optional<ColourMaterial> colour_material;
  Vec3 colour{1, 1, 1};
  std::string where;       // "objects[i]" for messages
  std::string scene_file;  // the scene file it comes from (messages)
  int lighting = 0;        // its lighting state: an index into Scene::lighting_sets (0 when the scene has none)
  // GL's depth state it is drawn with (a GL front end's; scene files: always on): depth_test = false (GL_DEPTH_TEST
  // off) draws its pixels over what is there in drawing order without writing depth; depth_write = false
  // (glDepthMask(GL_FALSE)) depth-tests without writing depth
  bool depth_test = true, depth_write = true;
};

// One lighting state of a stream: what the core holds in its global and light registers while a batch is lit. A
// scene file has one (its own global_ambient, local_viewer, separate_specular and lights); a GL front end hands over
// one per run of draws with the same state, in drawing order (the same state may come back), and the back end
// programs each by the register writes that differ from the state before it (render::prepare).
struct LightingSet {
  Vec3 global_ambient{0.2, 0.2, 0.2};
  bool local_viewer = false;
  bool separate_specular = false;
  std::vector<Light> lights;
};

struct ContactSheet {
  std::vector<std::optional<Shading>> modes;  // rows; nullopt = as in the scene
  std::vector<VariantId> units;               // columns after "exact" (each: image, difference)
  int cell_width = 160, cell_height = 160;
  std::optional<Camera> camera;
  std::vector<int> objects;                   // object indices shown (empty: all)
};

struct Scene {
  std::string file;        // the path it was read from (messages)
  std::string dir;         // its directory (OBJ paths are relative to it)
  int width = 256, height = 256;
  Vec3 background{0, 0, 0};
  Camera camera;
  Vec3 global_ambient{0.2, 0.2, 0.2};  // GL_LIGHT_MODEL_AMBIENT
  bool local_viewer = false;           // GL_LIGHT_MODEL_LOCAL_VIEWER
  bool separate_specular = false;      // GL_LIGHT_MODEL_COLOR_CONTROL: color_control "separate_specular"
  bool two_side = false;               // GL_LIGHT_MODEL_TWO_SIDE: back faces lit with −N and the back material
  bool blinn = true;                   // reflection: blinn (N·H, what GL does) or phong (R·V)
  std::string config = "default";      // the core's width (configs.json, frac <= 16)
  FlatRule flat_rule = FlatRule::Centroid;  // flat shading: centroid or GL_FLAT's provoking vertex
  std::vector<Light> lights;
  std::vector<Material> materials;
  std::vector<Object> objects;
  std::optional<ContactSheet> contact_sheet;
  // More than one lighting state (objects[i].lighting picks one): global_ambient, local_viewer, separate_specular
  // and lights above are then unused by the back end. Empty (scene files): the one state above.
  std::vector<LightingSet> lighting_sets;
  // The lighting states the back end uses: lighting_sets, or the one of the fields above.
  [[nodiscard]] std::vector<LightingSet> lighting_states() const {
    if (!lighting_sets.empty()) return lighting_sets;
    return {LightingSet{global_ambient, local_viewer, separate_specular, lights}};
  }
};

// Limits of the input (docs/scenes.md "Limits").
inline constexpr std::uint64_t kMaxSceneBytes = 16ull << 20;  // a scene file: at most 16 MiB
inline constexpr std::uint64_t kMaxObjBytes = 256ull << 20;   // an OBJ file: at most 256 MiB
inline constexpr int kMaxNesting = 64;                          // JSON arrays/objects nested at most 64 deep
inline constexpr int kMaxMembers = 256;                         // keys of one JSON object (materials: 256 names)
inline constexpr double kMaxCoord = 1e6;                        // |x| of a position, direction, translation, angle
inline constexpr double kMinLength = 1e-6;                      // smallest radius, size, |scale|
inline constexpr double kMaxLength = 1e4;                       // largest radius, size (|scale| up to kMaxCoord)
inline constexpr int kMaxFaceVertices = 255;                    // vertices of one OBJ face

// User text for a message: control characters (C0, DEL, C1) and bytes that are not UTF-8 shown as escapes
// (\n, \t, \r, \xNN, \u009b), at most `max_chars` characters (0: no limit) with "…" when cut. Every message that
// quotes a key, a name, a value or a file name goes through it, so a message stays one line and never
// drives the terminal.
std::string printable(std::string_view s, std::size_t max_chars = 60);

// Reads a regular file of at most `max_bytes` without ever blocking (a FIFO is refused before it is opened and
// opened O_NONBLOCK). On failure returns false and sets `why`: "no such file", "is a directory", "is a FIFO, not a
// regular file", "is a character device, not a regular file", "too many levels of symbolic links", "is N bytes,
// more than the limit of M MiB", ...
bool read_regular_file(const std::string& path, std::uint64_t max_bytes, std::string& text, std::string& why);

// Reads and checks a scene file. Throws SceneError (one line) on anything wrong.
Scene load_scene(const std::string& path);
// The same for a JSON text (`name` is used in messages and `dir` for OBJ paths).
Scene parse_scene(const std::string& text, const std::string& name, const std::string& dir);

}  // namespace shadecore::scene
