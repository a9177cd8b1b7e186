#include "ncpost/express/registry.hpp"

#include <algorithm>
#include <cstdint>
#include <span>
#include <system_error>
#include <utility>

#include "lexer.hpp"
#include "ncpost/p21/model.hpp"

namespace ncpost::express {

namespace detail {
// Defined in the generated sources of engine/express/cmake/embed_file.cmake.
std::string_view builtin_schema_bytes() noexcept;
std::string_view builtin_aim_schema_bytes() noexcept;
}  // namespace detail

namespace {

constexpr std::string_view kBuiltinOrigin = "<built-in>";
constexpr std::string_view kBuiltinAimOrigin = "<built-in AP238 AIM>";
// FILE_SCHEMA names that always mean a built-in, even if it failed to embed: the schemas that
// ISO 14649 part programs declare (FILE_SCHEMA(('MACHINING_SCHEMA','MILLING_SCHEMA'))), and the
// one AP238 AIM programs declare.
constexpr std::string_view kBuiltinNames[] = {"machining_schema", "milling_schema"};
constexpr std::string_view kBuiltinAimNames[] = {"integrated_cnc_schema"};

std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (const auto& item : items) {
    if (!out.empty()) out += ", ";
    out += item;
  }
  return out.empty() ? std::string("none") : out;
}

// Line and column of the FILE_SCHEMA header entity, which EXP-050 is about. The header is at
// the start of the file, so counting lines up to it is cheap even for a huge file.
std::pair<std::uint32_t, std::uint32_t> file_schema_position(const p21::Model& model) {
  const p21::Instance* header = model.header_entity("FILE_SCHEMA");
  if (header == nullptr || header->offset > model.text().size()) return {0, 0};
  const std::string_view before = model.text().substr(0, header->offset);
  const auto line = static_cast<std::uint32_t>(std::count(before.begin(), before.end(), '\n') + 1);
  const auto last_newline = before.rfind('\n');
  const auto column = static_cast<std::uint32_t>(
      last_newline == std::string_view::npos ? header->offset + 1 : before.size() - last_newline);
  return {line, column};
}

}  // namespace

std::string_view builtin_schema_text() noexcept {
  return detail::builtin_schema_bytes();
}

std::shared_ptr<const ParseResult> builtin_schema() {
  // A function-local static is initialised once, thread-safely.
  static const std::shared_ptr<const ParseResult> parsed =
      std::make_shared<const ParseResult>(parse_express(builtin_schema_text()));
  return parsed;
}

std::string_view builtin_aim_schema_text() noexcept {
  return detail::builtin_aim_schema_bytes();
}

std::shared_ptr<const ParseResult> builtin_aim_schema() {
  static const std::shared_ptr<const ParseResult> parsed =
      std::make_shared<const ParseResult>(parse_express(builtin_aim_schema_text()));
  return parsed;
}

const CheckPlan& SchemaSource::check_plan() const {
  std::call_once(plan_made_, [this] { plan_ = std::make_unique<const CheckPlan>(set()); });
  return *plan_;
}

// ---------------------------------------------------------------------------------------------

SchemaRegistry::SchemaRegistry() {
  const auto add_builtin = [this](std::string_view origin,
                                  std::shared_ptr<const ParseResult> parsed,
                                  std::span<const std::string_view> always) {
    auto source = std::make_unique<SchemaSource>();
    source->origin = std::string(origin);
    source->parsed = std::move(parsed);
    source->builtin = true;
    const SchemaSource* added = source.get();
    sources_.push_back(std::move(source));
    for (const Schema& schema : added->set().schemas()) names_.push_back(Name{schema.name, added});
    for (const std::string_view name : always)
      if (std::none_of(names_.begin(), names_.end(), [&](const Name& n) { return n.name == name; }))
        names_.push_back(Name{std::string(name), added});
    return added;
  };
  builtin_ = add_builtin(kBuiltinOrigin, builtin_schema(), kBuiltinNames);
  builtin_aim_ = add_builtin(kBuiltinAimOrigin, builtin_aim_schema(), kBuiltinAimNames);
}

std::string SchemaRegistry::normalise_name(std::string_view entry) {
  std::size_t begin = 0;
  while (begin < entry.size() && (entry[begin] == ' ' || entry[begin] == '\t')) ++begin;
  std::size_t end = begin;
  while (end < entry.size() && entry[end] != ' ' && entry[end] != '\t' && entry[end] != '{') ++end;
  return detail::to_lower(entry.substr(begin, end - begin));
}

std::vector<std::string> SchemaRegistry::file_schema_names(const p21::Model& model) {
  std::vector<std::string> names;
  const p21::Instance* header = model.header_entity("FILE_SCHEMA");
  if (header == nullptr || header->count == 0) return names;
  const p21::Value list = model.params(*header)[0];
  if (!list.is_list()) return names;
  for (const p21::Value item : model.items(list))
    if (item.kind() == p21::ValueKind::String) names.push_back(model.as_string(item));
  return names;
}

void SchemaRegistry::register_names(const SchemaSource& source,
                                    std::vector<diag::Diagnostic>* clashes) {
  for (const Schema& schema : source.set().schemas()) {
    const auto known = std::find_if(names_.begin(), names_.end(), [&](const Name& n) {
      return n.name == schema.name && !n.source->builtin;
    });
    if (known != names_.end()) {
      if (clashes != nullptr)
        clashes->push_back(diag::make(diag::Code::ExpSchemaDeclaredTwice, schema.pos.line,
                                      schema.pos.column,
                                      "SCHEMA " + schema.name + " is also declared in '" +
                                          known->source->origin + "'; that one is used"));
      continue;
    }
    // Directory schemas go in front of the built-in's names: they take precedence.
    const auto first_builtin =
        std::find_if(names_.begin(), names_.end(), [](const Name& n) { return n.source->builtin; });
    names_.insert(first_builtin, Name{schema.name, &source});
  }
}

std::vector<diag::Diagnostic> SchemaRegistry::add(std::string origin,
                                                  std::shared_ptr<const ParseResult> parsed) {
  std::vector<diag::Diagnostic> out;
  if (parsed == nullptr) return out;
  if (!parsed->ok()) {
    out.push_back(diag::make(diag::Code::ExpSchemaFileSkipped, 0, 0,
                             "'" + origin + "' has errors; none of its schemas is registered"));
    return out;
  }
  auto source = std::make_unique<SchemaSource>();
  source->origin = std::move(origin);
  source->parsed = std::move(parsed);
  register_names(*source, &out);
  sources_.push_back(std::move(source));
  return out;
}

std::vector<SchemaFileReport> SchemaRegistry::add_directory(const std::filesystem::path& directory,
                                                            SchemaCache& cache) {
  std::vector<SchemaFileReport> reports;
  std::error_code error;
  std::vector<std::filesystem::path> files;
  std::filesystem::directory_iterator it(directory, error);
  for (; !error && it != std::filesystem::directory_iterator(); it.increment(error)) {
    const auto& path = it->path();
    std::string extension = detail::to_lower(path.extension().string());
    std::error_code kind_error;
    if (extension == ".exp" && it->is_regular_file(kind_error)) files.push_back(path);
  }
  if (error) {
    reports.push_back(SchemaFileReport{
        directory,
        {diag::make(
            diag::Code::IoCannotRead, 0, 0,
            "cannot read schema directory '" + directory.string() + "': " + error.message())}});
    return reports;
  }
  // File-name order, so that which of two clashing files wins does not depend on the file system.
  std::sort(files.begin(), files.end());
  for (const auto& file : files) {
    auto parsed = cache.load_file(file);
    SchemaFileReport report{file, parsed->diagnostics};
    const auto added = add(file.string(), parsed);
    report.diagnostics.insert(report.diagnostics.end(), added.begin(), added.end());
    if (!report.diagnostics.empty()) reports.push_back(std::move(report));
  }
  return reports;
}

std::vector<diag::Diagnostic> SchemaRegistry::builtin_diagnostics() const {
  std::vector<diag::Diagnostic> out;
  const auto check = [&](std::string_view text, const SchemaSource& source, std::string_view file,
                         std::string_view what) {
    if (text.empty()) {
      out.push_back(diag::make(diag::Code::ExpBuiltinMissing, 0, 0,
                               "the built-in " + std::string(what) + " schema is empty: schemas/" +
                                   std::string(file) +
                                   " did not exist when this build was configured"));
    } else if (!source.parsed->diagnostics.empty()) {
      out.push_back(diag::make(
          diag::Code::ExpBuiltinMissing, 0, 0,
          "the built-in " + std::string(what) + " schema (schemas/" + std::string(file) + ") has " +
              std::to_string(source.parsed->diagnostics.size()) + " diagnostic(s), the first: " +
              diag::format(source.parsed->diagnostics.front(), file)));
    }
  };
  check(builtin_schema_text(), *builtin_, "iso14649.exp", "ISO 14649");
  check(builtin_aim_schema_text(), *builtin_aim_, "ap238_aim.exp", "AP238 AIM");
  return out;
}

const SchemaSource* SchemaRegistry::find(std::string_view schema_name) const {
  const std::string wanted = normalise_name(schema_name);
  for (const Name& n : names_)
    if (n.name == wanted) return n.source;
  return nullptr;
}

std::vector<std::string> SchemaRegistry::known_names() const {
  std::vector<std::string> names;
  for (const Name& n : names_) names.push_back(n.name);
  std::sort(names.begin(), names.end());
  names.erase(std::unique(names.begin(), names.end()), names.end());
  return names;
}

SchemaSelection SchemaRegistry::select_for(const p21::Model& model) const {
  return select_for(model, {});
}

const SchemaSource* SchemaRegistry::find(std::string_view schema_name,
                                         std::span<const NameAlias> aliases,
                                         const NameAlias** used) const {
  if (const SchemaSource* source = find(schema_name)) return source;
  const std::string wanted = normalise_name(schema_name);
  for (const NameAlias& alias : aliases) {
    if (alias.written != wanted) continue;
    if (const SchemaSource* source = find(alias.read_as)) {
      if (used != nullptr) *used = &alias;
      return source;
    }
  }
  return nullptr;
}

SchemaSelection SchemaRegistry::select_for(const p21::Model& model,
                                           std::span<const NameAlias> aliases) const {
  SchemaSelection selection;
  const std::vector<std::string> entries = file_schema_names(model);
  const std::string* chosen = nullptr;
  for (const std::string& entry : entries) {
    selection.source = find(entry, aliases, nullptr);
    if (selection.source != nullptr) {
      chosen = &entry;
      break;
    }
  }
  const auto [line, column] = file_schema_position(model);
  const auto unknown = [&, line = line, column = column](const std::string& message) {
    selection.diagnostics.push_back(
        diag::make(diag::Code::ExpNoSchemaForModel, line, column, message));
  };
  if (entries.empty()) {
    unknown("the file names no schema in FILE_SCHEMA; known: " + join(known_names()));
    return selection;
  }
  for (const std::string& entry : entries) {
    const NameAlias* alias = nullptr;
    const SchemaSource* source = find(entry, aliases, &alias);
    if (source == nullptr)
      unknown("no schema for FILE_SCHEMA '" + entry + "'; known: " + join(known_names()));
    else if (source != selection.source)
      unknown("FILE_SCHEMA '" + entry + "' is declared in '" + source->origin + "', not with '" +
              *chosen + "' in '" + selection.source->origin + "'; only '" +
              selection.source->origin + "' is used");
    else if (alias != nullptr)
      selection.diagnostics.push_back(
          diag::make(diag::Code::InteropSchemaName, line, column,
                     "FILE_SCHEMA '" + entry + "' is read as '" + std::string(alias->read_as) +
                         "', the ISO 14649 schema under another name (docs/interoperability.md, "
                         "\"Variants\"): the file is checked against '" +
                         source->origin + "'"));
  }
  return selection;
}

SchemaSelection SchemaRegistry::select_or_builtin(const p21::Model& model) const {
  return select_or_builtin(model, {});
}

SchemaSelection SchemaRegistry::select_or_builtin(const p21::Model& model,
                                                  std::span<const NameAlias> aliases) const {
  SchemaSelection selection = select_for(model, aliases);
  if (selection.source == nullptr) {
    selection.source = builtin_;
    selection.fallback = true;
    selection.diagnostics.push_back(diag::make(
        diag::Code::ExpBuiltinFallback, 0, 0,
        "no schema for the file's FILE_SCHEMA; the built-in ISO 14649 schema is used to read "
        "it, and the file is not checked against a schema"));
  }
  return selection;
}

}  // namespace ncpost::express
