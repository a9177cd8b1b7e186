#include "geometry.hpp"

#include "ncpost/p21/reader.hpp"

namespace ncpost::stepnc::detail {

namespace {
constexpr double kUnitTolerance = 1e-9;
// An entity is asked for a few attributes (a placement: location, axis, ref_direction): room
// for them at once instead of growing the list one allocation at a time.
constexpr std::size_t kRememberedPerKeyword = 8;
}  // namespace

bool Frame::identity() const {
  const auto same = [](Vec3 a, Vec3 b) { return (a - b).length() < 1e-12; };
  return same(origin, {}) && same(x, {1, 0, 0}) && same(y, {0, 1, 0}) && same(z, {0, 0, 1});
}

Frame inverse(const Frame& f) {
  Frame out;
  out.x = {f.x.x, f.y.x, f.z.x};
  out.y = {f.x.y, f.y.y, f.z.y};
  out.z = {f.x.z, f.y.z, f.z.z};
  out.origin = {-f.x.dot(f.origin), -f.y.dot(f.origin), -f.z.dot(f.origin)};
  return out;
}

std::string describe(const p21::Model& model, const p21::Instance& instance) {
  return "#" + std::to_string(instance.id) + " (" + std::string(model.type_name(instance)) + ")";
}

GeometryReader::GeometryReader(const p21::Model& model, const AttributeReader& attributes,
                               std::vector<diag::Diagnostic>& diagnostics)
    : model_(model), attributes_(attributes), diagnostics_(diagnostics) {}

void GeometryReader::error(diag::Code code, const p21::Instance& at, std::string message) {
  if (!lines_) lines_.emplace(model_.text());
  const auto pos = lines_->at(at.offset);
  diagnostics_.push_back(diag::make(code, pos.line, pos.column, std::move(message)));
}

bool GeometryReader::is_a(const p21::Instance& instance, std::string_view entity) {
  // Simple instances: the answer per (keyword, literal) is remembered.
  if (!model_.is_complex(instance)) {
    if (instance.keyword >= kinds_.size()) kinds_.resize(model_.keyword_count());
    for (const auto& [literal, answer] : kinds_[instance.keyword])
      if (literal == entity.data()) return answer;
  }
  auto it = entities_.find(entity);
  if (it == entities_.end())
    it = entities_.emplace(entity, attributes_.schema().find_entity(entity)).first;
  const bool answer = attributes_.is_a(instance, it->second);
  if (!model_.is_complex(instance)) {
    auto& answers = kinds_[instance.keyword];
    if (answers.empty()) answers.reserve(kRememberedPerKeyword);
    answers.emplace_back(entity.data(), answer);
  }
  return answer;
}

std::optional<p21::Value> GeometryReader::get(const p21::Instance& instance,
                                              std::string_view name) {
  const express::Entity* e = attributes_.entity(instance);
  if (e == nullptr) return attributes_.get(instance, name);  // complex or unknown
  if (instance.keyword >= positions_.size()) positions_.resize(model_.keyword_count());
  auto& known = positions_[instance.keyword];
  int position = -2;
  for (const auto& [literal, at] : known)
    if (literal == name.data()) position = at;
  if (position == -2) {
    const auto index = e->attribute_index(name);
    position = index ? static_cast<int>(*index) : -1;
    if (known.empty()) known.reserve(kRememberedPerKeyword);
    known.emplace_back(name.data(), position);
  }
  const auto params = model_.params(instance);
  if (position < 0 || static_cast<std::size_t>(position) >= params.size()) return std::nullopt;
  return params[static_cast<std::size_t>(position)];
}

const p21::Instance* GeometryReader::instance(std::optional<p21::Value> reference,
                                              std::string_view expected, const p21::Instance* owner,
                                              std::string_view attribute) {
  const p21::Instance* target =
      reference && reference->is_reference() ? model_.find(reference->id()) : nullptr;
  // The message is built only when there is something to report: this runs per reference.
  const auto where = [&] {
    return owner ? describe(model_, *owner) + " attribute " + std::string(attribute)
                 : std::string("a reference");
  };
  if (target == nullptr) {
    if (owner)
      error(diag::Code::StepncBadAttribute, *owner, where() + " does not refer to an instance");
    return nullptr;
  }
  if (!expected.empty() && !is_a(*target, expected)) {
    error(diag::Code::StepncWrongType, owner ? *owner : *target,
          where() + " refers to " + describe(model_, *target) + ", which is not a " +
              std::string(expected));
    return nullptr;
  }
  return target;
}

std::optional<double> GeometryReader::number(const p21::Instance& owner, std::string_view name) {
  const auto v = get(owner, name);
  if (!v || !v->is_number()) return std::nullopt;
  const double d = model_.as_real(*v);
  if (!std::isfinite(d)) {
    error(diag::Code::StepncBadGeometry, owner,
          describe(model_, owner) + " attribute " + std::string(name) + " is not a finite number");
    return std::nullopt;
  }
  return d;
}

std::optional<Vec3> GeometryReader::point(std::optional<p21::Value> reference) {
  const p21::Instance* p = instance(reference, "cartesian_point");
  if (p == nullptr) return std::nullopt;
  const auto coordinates = get(*p, "coordinates");
  if (!coordinates || !coordinates->is_list() || coordinates->count() < 2 ||
      coordinates->count() > 3) {
    error(diag::Code::StepncBadGeometry, *p,
          describe(model_, *p) + " needs two or three coordinates");
    return std::nullopt;
  }
  const auto items = model_.items(*coordinates);
  std::array<double, 3> xyz{0, 0, 0};
  for (std::size_t i = 0; i < items.size(); ++i) {
    const p21::Value c =
        items[i].kind() == p21::ValueKind::Typed ? model_.typed_child(items[i]) : items[i];
    xyz[i] = c.is_number() ? model_.as_real(c) : std::nan("");
    if (!std::isfinite(xyz[i])) {
      error(diag::Code::StepncBadGeometry, *p,
            describe(model_, *p) + " coordinate " + std::to_string(i + 1) +
                " is not a finite number");
      return std::nullopt;
    }
  }
  return Vec3{xyz[0], xyz[1], xyz[2]};
}

std::optional<Vec3> GeometryReader::direction(std::optional<p21::Value> reference) {
  const p21::Instance* d = instance(reference, "direction");
  if (d == nullptr) return std::nullopt;
  const auto ratios = get(*d, "direction_ratios");
  if (!ratios || !ratios->is_list() || ratios->count() < 2 || ratios->count() > 3) {
    error(diag::Code::StepncBadGeometry, *d, describe(model_, *d) + " needs two or three ratios");
    return std::nullopt;
  }
  const auto items = model_.items(*ratios);
  Vec3 v{model_.as_real(items[0]), model_.as_real(items[1]),
         items.size() > 2 ? model_.as_real(items[2]) : 0.0};
  const double length = v.length();
  if (!v.finite() || length < kUnitTolerance) {
    error(diag::Code::StepncBadGeometry, *d,
          describe(model_, *d) + " has no direction (zero or non-finite ratios)");
    return std::nullopt;
  }
  return v * (1.0 / length);
}

std::optional<Frame> GeometryReader::placement(std::optional<p21::Value> reference) {
  const p21::Instance* a = instance(reference, "axis2_placement_3d");
  if (a == nullptr) return std::nullopt;
  const auto location = point(get(*a, "location"));
  if (!location) return std::nullopt;
  Vec3 z{0, 0, 1};
  Vec3 ref{1, 0, 0};
  if (const auto axis = get(*a, "axis"); axis && !axis->is_omitted()) {
    const auto d = direction(axis);
    if (!d) return std::nullopt;
    z = *d;
  }
  if (const auto r = get(*a, "ref_direction"); r && !r->is_omitted()) {
    const auto d = direction(r);
    if (!d) return std::nullopt;
    ref = *d;
  } else if (std::abs(z.dot(ref)) > 1 - 1e-9) {
    ref = {0, 0, 1};  // ISO 10303-42's default when +X is parallel to the axis
  }
  // x is the projection of ref_direction onto the plane normal to the axis.
  const Vec3 projected = ref - z * ref.dot(z);
  if (projected.length() < 1e-9) {
    error(diag::Code::StepncBadGeometry, *a,
          describe(model_, *a) + " has a ref_direction parallel to its axis");
    return std::nullopt;
  }
  Frame f;
  f.origin = *location;
  f.z = z;
  f.x = projected * (1.0 / projected.length());
  f.y = f.z.cross(f.x);
  return f;
}

}  // namespace ncpost::stepnc::detail
