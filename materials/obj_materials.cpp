#include "materials/obj_materials.hpp"

#include <cstdio>
#include <set>

#include "geometry/text_scanner.hpp"
#include "materials/glass_transmittance.hpp"
#include "materials/radiance_luminance.hpp"

namespace daylit {

namespace {

// Honeybee's generic wall (generic_wall_0.50) for faces without a material daylit knows.
constexpr double kDefaultReflectance = 0.5;

std::string number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", x);
  return buf;
}

double grey(const std::array<double, 3>& c) { return radiance_luminance(c[0], c[1], c[2]); }

// Faces counted for one reason, reported once with the first of them.
struct Tally {
  long count = 0;
  const ObjFace* first = nullptr;
  std::string first_material;
  void add(const ObjFace& f, const std::string& material = {}) {
    if (count++ == 0) {
      first = &f;
      first_material = material;
    }
  }
};

std::string faces(long n) { return std::to_string(n) + (n == 1 ? " face" : " faces"); }

class ObjAssembler {
 public:
  ObjAssembler(const ObjModel& model, const ObjMaterialMap* map) : model_(model), map_(map) {}

  RadContent assemble() {
    content_.notices = model_.notices;
    check_libraries();
    for (const ObjFace& f : model_.faces) face(f);
    finish_notices();
    return std::move(content_);
  }

 private:
  // The names a group rule matches: the face's groups and its object.
  static std::vector<std::string> group_names(const ObjFace& f) {
    std::vector<std::string> names = f.groups;
    if (!f.object.empty()) names.push_back(f.object);
    return names;
  }

  const ObjSurfaceRule* rule_of(const ObjFace& f, bool& from_group) const {
    from_group = false;
    if (!map_) return nullptr;
    if (const ObjSurfaceRule* g = match_rule(map_->groups, group_names(f))) {
      from_group = true;
      return g;
    }
    if (f.polygon.material.empty()) return nullptr;
    return match_rule(map_->materials, {f.polygon.material});
  }

  const MtlMaterial* mtl_of(const ObjFace& f) const {
    const auto it = model_.materials.find(f.polygon.material);
    return it == model_.materials.end() ? nullptr : &it->second;
  }

  // A mtllib that could not be read matters when some face takes a value from the .mtl.
  void check_libraries() {
    if (model_.missing_libraries.empty()) return;
    const ObjFace* needing = nullptr;
    long needing_count = 0;
    for (const ObjFace& f : model_.faces) {
      bool from_group;
      const ObjSurfaceRule* r = rule_of(f, from_group);
      if ((!r || !r->complete()) && !mtl_of(f)) {
        if (needing_count++ == 0) needing = &f;
      }
    }
    const auto& lib = model_.missing_libraries.front();
    if (needing)
      throw input_error(lib.where, "mtllib " + printable(lib.name) + ": cannot read " + lib.path + ", and " +
                                       faces(needing_count) + " take their material from it (" +
                                       printable(needing->polygon.material.empty() ? needing->polygon.name
                                                                                    : needing->polygon.material) +
                                       " first): put the .mtl beside the .obj, or give those materials a role with all "
                                       "its values in --obj-materials");
    // Not needed: each face's material is defined in a library that was read, or the map gives the
    // face its role with all its values (or there are no faces).
    for (const auto& l : model_.missing_libraries)
      content_.notices.push_back(l.where.str() + ": mtllib " + printable(l.name) + " could not be read (" + l.path +
                                 "); not needed: no face takes a value from it" +
                                 (map_ ? " (" + map_->path + " gives the others' roles and values)" : std::string()));
  }

  void face(const ObjFace& f) {
    bool from_group = false;
    const ObjSurfaceRule* r = rule_of(f, from_group);
    if (r) used_rules_.insert(r);
    const MtlMaterial* m = mtl_of(f);
    const std::string& usemtl = f.polygon.material;
    const std::string mtl_name = usemtl.empty() ? "(no material)" : usemtl;
    // The Radiance material's name: the usemtl name, unless a group rule decides; then the rule's
    // pattern, with the usemtl name where the .mtl still gives a value.
    const std::string name = from_group ? "group " + r->pattern + (r->complete() ? "" : " / " + mtl_name) : mtl_name;
    const ObjRole role = r ? r->role : m && mtl_transmittance(*m) ? ObjRole::aperture : ObjRole::opaque;
    if (m) note_mtl_properties(*m, role, r);
    if (role == ObjRole::ignore) {
      ignored_.add(f, r->where.str());
      return;
    }
    Polygon p = f.polygon;
    p.material = name;
    if (role == ObjRole::opaque) {
      ++opaque_;
      define(name, [&] {
        if (r && r->reflectance) {
          const double rho = *r->reflectance;
          return Material{name, "plastic", {}, {rho, rho, rho, 0, 0}, r->where};
        }
        if (m && m->kd) return Material{name, "plastic", {}, {(*m->kd)[0], (*m->kd)[1], (*m->kd)[2], 0, 0}, m->where};
        const double rho = kDefaultReflectance;
        return Material{name, "plastic", {}, {rho, rho, rho, 0, 0}, m ? m->where : f.polygon.where};
      });
      if (!(r && r->reflectance) && !(m && m->kd)) defaulted_.add(f, mtl_name);
      content_.polygons.push_back({std::move(p), false});
      return;
    }
    ++apertures_;
    const std::optional<double> mtl_t = m ? mtl_transmittance(*m) : std::nullopt;
    if (role == ObjRole::aperture) {
      double t = 1;
      SourceLocation where = f.polygon.where;
      if (r && r->transmittance) {
        t = *r->transmittance;
        where = r->where;
      } else if (mtl_t) {
        t = *mtl_t;
        where = m->where;
        if (!r && !content_.materials.count(name))
          transparent_.push_back("'" + mtl_name + "' " + number(t) + " (" + describe_transparency(*m) + ")");
      } else {
        open_.add(f, r ? r->where.str() : std::string());
      }
      define(name, [&] { return Material{name, "trans", {}, {t, t, t, 0, 0, 1, 1}, where}; });
    } else {  // glass
      define(name, [&] {
        const double n = r->refractive_index.value_or(1.52);
        if (r->transmissivity) {
          std::vector<double> reals(3, *r->transmissivity);
          if (r->refractive_index) reals.push_back(n);
          return Material{name, "glass", {}, reals, r->where};
        }
        const std::optional<double> t = r->transmittance ? r->transmittance : mtl_t;
        if (!t)
          throw Error(r->where.str() + ": glass for " + printable(mtl_name) +
                      " needs a transmittance (or transmissivity): the .mtl gives none (the material is not "
                      "transparent there)");
        const std::optional<double> tn = glass_transmissivity(*t, n);
        if (!tn)
          throw Error(r->where.str() + ": transmittance " + number(*t) + " at normal incidence is more than glass of "
                      "refractive index " + number(n) + " passes (" + number(glass_transmittance({{1, 1, 1}, n}, 1.0)) +
                      ": its surfaces reflect the rest); use the role aperture for an opening");
        std::vector<double> reals(3, *tn);
        if (r->refractive_index) reals.push_back(n);
        return Material{name, "glass", {}, reals, r->transmittance ? r->where : m->where};
      });
    }
    content_.polygons.push_back({std::move(p), true});
  }

  template <class Make>
  void define(const std::string& name, Make make) {
    if (content_.materials.count(name)) return;
    Material material = make();
    check_material(material);
    content_.materials[name] = std::move(material);
  }

  static std::string describe_transparency(const MtlMaterial& m) {
    if (m.dissolve && *m.dissolve < 1)
      return "d " + number(*m.dissolve) + (m.tf ? ", Tf " + number(grey(*m.tf)) + " grey" : std::string());
    return "illum " + std::to_string(*m.illum) + ", Tf " + number(grey(*m.tf)) + " grey";
  }

  // What of a material daylit leaves aside, each said once per material.
  void note_mtl_properties(const MtlMaterial& m, ObjRole role, const ObjSurfaceRule* r) {
    if (!noted_.insert(m.name).second) return;
    const bool kd_used = role == ObjRole::opaque && !(r && r->reflectance);
    if (kd_used && m.ks && grey(*m.ks) > 0) specular_.push_back(m.name);
    if (kd_used && m.texture) textured_.push_back(m.name);
    if (m.ke && grey(*m.ke) > 0) emissive_.push_back(m.name);
    if (m.alpha_texture) alpha_textured_.push_back(m.name);
    if (m.tf && !mtl_transmittance(m) && role == ObjRole::opaque) filter_ignored_.push_back(m.name);
  }

  static std::string list(const std::vector<std::string>& names) {
    std::string s;
    for (std::size_t i = 0; i < names.size() && i < 4; ++i) s += (i ? ", " : "") + printable(names[i]);
    if (names.size() > 4) s += " and " + std::to_string(names.size() - 4) + " more";
    return s;
  }

  void finish_notices() {
    auto& notices = content_.notices;
    const std::string& obj = model_.path;
    std::string libs;
    for (const auto& f : model_.mtl_files) libs += (libs.empty() ? "" : ", ") + f;
    const ObjOptions& o = model_.options;
    notices.push_back(obj + ": " + faces(long(model_.faces.size())) + " (" + std::to_string(model_.vertices) +
                      " vertices; materials from " + (libs.empty() ? "no .mtl" : libs) +
                      (map_ ? " and " + map_->path : std::string()) + "): " + std::to_string(opaque_) + " opaque, " +
                      std::to_string(apertures_) + " apertures, " + std::to_string(ignored_.count) + " left out; read " +
                      (o.up == ObjUpAxis::z ? "z up" : "y up (turned to z up)") + " at " + number(o.metres_per_unit) +
                      " m per unit (--obj-up, --obj-scale; Blender writes y up by default)");
    if (!transparent_.empty()) {
      std::string s;
      for (std::size_t i = 0; i < transparent_.size() && i < 4; ++i) s += (i ? ", " : "") + transparent_[i];
      if (transparent_.size() > 4) s += " and " + std::to_string(transparent_.size() - 4) + " more";
      notices.push_back(obj + ": materials transparent in the .mtl are apertures of constant transmittance: " + s +
                        "; map them to the role glass in --obj-materials for Radiance's glass, whose transmittance "
                        "falls with the angle of incidence");
      if (opaque_ == 0)
        notices.push_back(obj + ": every face is transparent in the .mtl: if the exporter wrote Tr as opacity (some "
                                "do), map the opaque materials with --obj-materials");
    }
    if (defaulted_.count)
      notices.push_back(defaulted_.first->polygon.where.str() + ": " + faces(defaulted_.count) +
                        " without a material daylit knows (no usemtl, a usemtl no .mtl defines, or no Kd: " +
                        printable(defaulted_.first_material) + " first) are opaque with reflectance " +
                        number(kDefaultReflectance) + " (Honeybee's generic wall); give them a role in --obj-materials");
    if (open_.count)
      notices.push_back(open_.first->polygon.where.str() + ": " + faces(open_.count) +
                        " of aperture rules are open (transmittance 1): the rule gives no transmittance and their "
                        "material is not transparent in the .mtl (" + open_.first_material + " first)");
    if (ignored_.count)
      notices.push_back(ignored_.first->polygon.where.str() + ": " + faces(ignored_.count) + " left out (role ignore, " +
                        ignored_.first_material + " first)");
    if (!specular_.empty())
      notices.push_back(obj + ": the specular Ks/Ns of " + list(specular_) +
                        " is not added: the surface is diffuse with its Kd alone (exporters write Ks as a display "
                        "highlight, which with Kd can exceed 1); give a reflectance in --obj-materials to change it");
    if (!textured_.empty())
      notices.push_back(obj + ": the map_Kd textures of " + list(textured_) + " are not read: their Kd is used");
    if (!alpha_textured_.empty())
      notices.push_back(obj + ": the map_d transparency textures of " + list(alpha_textured_) + " are not read: their d is used");
    if (!emissive_.empty())
      notices.push_back(obj + ": the emission Ke of " + list(emissive_) + " is left out: the sky comes from --sky");
    if (!filter_ignored_.empty())
      notices.push_back(obj + ": the Tf of " + list(filter_ignored_) +
                        " is ignored: with d = 1 and an illum other than 6 or 7 the material is opaque (3ds Max writes "
                        "Tf 1 1 1 on every material)");
    if (map_)
      for (const auto* rules : {&map_->materials, &map_->groups})
        for (const auto& r : *rules)
          if (!used_rules_.count(&r))
            notices.push_back(r.where.str() + ": matches no face of " + obj + " (a misspelt name?)");
  }

  const ObjModel& model_;
  const ObjMaterialMap* map_;
  RadContent content_;
  long opaque_ = 0, apertures_ = 0;
  Tally ignored_, defaulted_, open_;
  std::set<const ObjSurfaceRule*> used_rules_;
  std::set<std::string> noted_;
  std::vector<std::string> transparent_, specular_, textured_, alpha_textured_, emissive_, filter_ignored_;
};

}  // namespace

std::optional<double> mtl_transmittance(const MtlMaterial& m) {
  if (m.dissolve && *m.dissolve < 1) return (1 - *m.dissolve) * (m.tf ? grey(*m.tf) : 1.0);
  if (m.illum && (*m.illum == 6 || *m.illum == 7) && m.tf && grey(*m.tf) > 0) return grey(*m.tf);
  return std::nullopt;
}

RadContent obj_rad_content(const ObjModel& model, const ObjMaterialMap* map) { return ObjAssembler(model, map).assemble(); }

}  // namespace daylit
