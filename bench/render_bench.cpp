// The render stage (issue 6 §5), three measurements:
//
//   render_bench plain-xsl OUT.xsl
//       writes a plain XSLT 1.0 stylesheet (no ext: functions; G0/G1/G2/G3 lines with
//       format-number) that both libxslt-through-ncpost and xsltproc can run.
//   render_bench transform XSL|PROFILE XML [RUNS]
//       xslt::transform of the whole document XML with the stylesheet compiled once: parse of the
//       document + apply + serialise, as xsltproc's "Parsing document" + "Applying stylesheet".
//       XSL is a file ending in .xsl, or a profile id (its post.xsl with its job config/params).
//   render_bench cache PROFILE FILE [RUNS]
//       time per post of a small program: the profile's cached compiled stylesheet against
//       xslt::compile of post.xsl for every post (interpretation done once, outside the timing).
//   render_bench pipeline PROFILE FILE [RUNS] [BATCH_BYTES] [RENDER_THREAD_MIN] [LOAD_HELPERS]
//       `ncpost post` without the output: pipeline::load, then pipeline::post to a sink that
//       drops the text; MB/s of P21 in, time to the first text, pieces of text handed on, and
//       peak RSS (after the load, after the render). BATCH_BYTES sets RenderOptions::batch_bytes
//       (0: one transform per chunk, as before batching; default: the renderer's default);
//       RENDER_THREAD_MIN sets PostOptions::render_thread_min_instances (0: one thread);
//       LOAD_HELPERS threads read and check the file in pieces (default: one fewer than the
//       cores, as `ncpost post`; 0: in order).

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "bench_support.hpp"
#include "ncpost/canon/sink.hpp"
#include "ncpost/express/registry.hpp"
#include "ncpost/parallel/pieces.hpp"
#include "ncpost/pipeline/load.hpp"
#include "ncpost/pipeline/post.hpp"
#include "ncpost/profile/profile.hpp"
#include "ncpost/render/render.hpp"
#include "ncpost/stepnc/interpreter.hpp"
#include "ncpost/xslt/xslt.hpp"

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

struct Stats {
  double best = 0;
  double median = 0;
};

Stats stats(std::vector<double> times) {
  std::sort(times.begin(), times.end());
  return {times.front(), times[times.size() / 2]};
}

// Comparable work to a profile's post.xsl, in plain XSLT 1.0: one line per motion, numbers
// through format-number, arcs as G2/G3 with I J from the centre.
// clang-format off
constexpr const char* kPlainXsl = R"xsl(<?xml version="1.0"?>
<xsl:stylesheet version="1.0" xmlns:xsl="http://www.w3.org/1999/XSL/Transform">
  <xsl:output method="text"/>
  <xsl:strip-space elements="*"/>
  <xsl:decimal-format name="nc" NaN="0"/>
  <xsl:template name="n">
    <xsl:param name="v"/>
    <xsl:value-of select="format-number($v, '0.0##', 'nc')"/>
  </xsl:template>
  <xsl:template name="xyz">
    <xsl:text> X</xsl:text><xsl:call-template name="n"><xsl:with-param name="v" select="@x"/></xsl:call-template>
    <xsl:text> Y</xsl:text><xsl:call-template name="n"><xsl:with-param name="v" select="@y"/></xsl:call-template>
    <xsl:text> Z</xsl:text><xsl:call-template name="n"><xsl:with-param name="v" select="@z"/></xsl:call-template>
  </xsl:template>
  <xsl:template match="/">
    <xsl:text>%&#10;</xsl:text>
    <xsl:apply-templates select="program/chunk"/>
    <xsl:text>M30&#10;%&#10;</xsl:text>
  </xsl:template>
  <xsl:template match="chunk"><xsl:apply-templates/></xsl:template>
  <xsl:template match="workingstep">
    <xsl:value-of select="concat('(', translate(@name, '()', '[]'), ')&#10;')"/>
    <xsl:apply-templates/>
  </xsl:template>
  <xsl:template match="STRAIGHT_TRAVERSE">
    <xsl:text>G0</xsl:text><xsl:call-template name="xyz"/><xsl:text>&#10;</xsl:text>
  </xsl:template>
  <xsl:template match="STRAIGHT_FEED">
    <xsl:text>G1</xsl:text><xsl:call-template name="xyz"/><xsl:text>&#10;</xsl:text>
  </xsl:template>
  <xsl:template match="ARC_FEED">
    <xsl:variable name="sx" select="preceding-sibling::*[@x][1]/@x"/>
    <xsl:variable name="sy" select="preceding-sibling::*[@y][1]/@y"/>
    <xsl:choose><xsl:when test="@turns &lt; 0">G2</xsl:when><xsl:otherwise>G3</xsl:otherwise></xsl:choose>
    <xsl:call-template name="xyz"/>
    <xsl:text> I</xsl:text><xsl:call-template name="n"><xsl:with-param name="v" select="@cx - $sx"/></xsl:call-template>
    <xsl:text> J</xsl:text><xsl:call-template name="n"><xsl:with-param name="v" select="@cy - $sy"/></xsl:call-template>
    <xsl:text>&#10;</xsl:text>
  </xsl:template>
  <xsl:template match="SET_FEED_RATE">
    <xsl:text>F</xsl:text><xsl:call-template name="n"><xsl:with-param name="v" select="@rate"/></xsl:call-template><xsl:text>&#10;</xsl:text>
  </xsl:template>
  <xsl:template match="SET_SPINDLE_SPEED">
    <xsl:value-of select="concat('S', format-number(@rpm, '0'), '&#10;')"/>
  </xsl:template>
  <xsl:template match="CHANGE_TOOL">
    <xsl:value-of select="concat('T', @slot, ' M6&#10;')"/>
  </xsl:template>
  <xsl:template match="*"/>
</xsl:stylesheet>
)xsl";
// clang-format on

class Collect final : public ncpost::canon::Sink {
 public:
  void call(const ncpost::canon::Call& c) override { calls.push_back(c); }
  std::vector<ncpost::canon::Call> calls;
};

void print(const std::vector<ncpost::diag::FileDiagnostic>& diagnostics) {
  for (const auto& d : diagnostics) std::cerr << ncpost::diag::format(d) << '\n';
}

std::shared_ptr<const ncpost::profile::LoadedProfile> load_profile(const std::string& id) {
  static ncpost::profile::ProfileStore store;
  std::vector<ncpost::diag::FileDiagnostic> diagnostics;
  auto loaded = store.load(id, diagnostics);
  print(diagnostics);
  return loaded;
}

int plain_xsl(const std::string& out) {
  std::ofstream(out, std::ios::binary) << kPlainXsl;
  return 0;
}

int transform(const std::string& xsl, const std::string& xml_path, int runs) {
  const std::string xml = ncpost::bench::slurp(xml_path);
  std::shared_ptr<const ncpost::xslt::CompiledStylesheet> stylesheet;
  ncpost::xslt::JobConfig config;
  ncpost::xslt::Params params;
  ncpost::xslt::Limits limits;
  limits.max_steps = 0;
  limits.max_xpath_ops = 0;
  limits.max_time = std::chrono::milliseconds{0};
  if (xsl.ends_with(".xsl")) {
    const std::filesystem::path file = std::filesystem::absolute(xsl);
    const std::vector<std::filesystem::path> roots{file.parent_path()};
    auto compiled = ncpost::xslt::compile(file, roots);
    print(compiled.diagnostics);
    stylesheet = compiled.stylesheet;
  } else {
    const auto loaded = load_profile(xsl);
    if (!loaded) return 1;
    stylesheet = loaded->stylesheet;
    config = ncpost::profile::job_config(loaded->profile);
    params = {{"program_number", std::to_string(loaded->profile.program_number)},
              {"profile_id", loaded->profile.id},
              {"arcs", loaded->profile.arcs == ncpost::profile::Arcs::R ? "r" : "ijk"},
              {"tool", "0"}};
  }
  if (!stylesheet) return 1;
  std::vector<double> times;
  std::size_t out_bytes = 0;
  for (int i = 0; i < runs; ++i) {
    ncpost::xslt::JobState job(config, limits);
    const auto start = Clock::now();
    const auto result = ncpost::xslt::transform(*stylesheet, xml, job, params);
    times.push_back(seconds_since(start));
    if (!result.ok) {
      print(result.diagnostics);
      return 1;
    }
    out_bytes = result.output.size();
  }
  const Stats s = stats(times);
  std::cout << "stylesheet=" << xsl << " xml=" << xml_path << " xml_bytes=" << xml.size()
            << " out_bytes=" << out_bytes << " runs=" << runs
            << " transform_best_ms=" << s.best * 1e3 << " transform_median_ms=" << s.median * 1e3
            << '\n';
  return 0;
}

int cache(const std::string& id, const std::string& file, int runs) {
  const auto loaded = load_profile(id);
  if (!loaded) return 1;
  const ncpost::express::SchemaRegistry registry;
  auto model = ncpost::pipeline::load(ncpost::bench::slurp(file), registry);
  const ncpost::stepnc::AttributeReader attributes(model.model, *model.schema);
  Collect calls;
  if (!ncpost::stepnc::interpret(model.model, attributes, calls).ok()) {
    std::cerr << "interpreted with errors\n";
    return 1;
  }
  const std::filesystem::path post = loaded->directory / "post.xsl";
  const std::vector<std::filesystem::path> roots{loaded->directory,
                                                 loaded->directory.parent_path() / "common"};
  std::vector<double> cached_times;
  std::vector<double> compile_times;
  std::vector<double> compile_only_times;
  std::size_t out_bytes = 0;
  for (int i = 0; i < runs; ++i) {
    std::vector<ncpost::diag::FileDiagnostic> diagnostics;
    auto start = Clock::now();
    out_bytes = ncpost::render::render_program(*loaded, calls.calls, diagnostics).size();
    cached_times.push_back(seconds_since(start));

    start = Clock::now();
    auto compiled = ncpost::xslt::compile(post, roots);
    compile_only_times.push_back(seconds_since(start));
    if (!compiled.ok()) {
      print(compiled.diagnostics);
      return 1;
    }
    ncpost::profile::LoadedProfile fresh = *loaded;
    fresh.stylesheet = compiled.stylesheet;
    const auto text = ncpost::render::render_program(fresh, calls.calls, diagnostics);
    compile_times.push_back(seconds_since(start));
    if (text.size() != out_bytes || ncpost::diag::has_errors(diagnostics)) {
      print(diagnostics);
      return 1;
    }
  }
  const Stats c = stats(cached_times);
  const Stats r = stats(compile_times);
  const Stats k = stats(compile_only_times);
  std::cout << "profile=" << id << " file=" << file << " calls=" << calls.calls.size()
            << " out_bytes=" << out_bytes << " runs=" << runs << " cached_best_ms=" << c.best * 1e3
            << " cached_median_ms=" << c.median * 1e3 << " recompile_best_ms=" << r.best * 1e3
            << " recompile_median_ms=" << r.median * 1e3 << " compile_only_best_ms=" << k.best * 1e3
            << " compile_only_median_ms=" << k.median * 1e3
            << " speedup_median=" << r.median / c.median << '\n';
  return 0;
}

int pipeline(const std::string& id, const std::string& file, int runs,
             std::optional<std::size_t> batch_bytes, std::optional<std::size_t> render_thread_min,
             std::size_t load_helpers) {
  const auto loaded = load_profile(id);
  if (!loaded) return 1;
  const ncpost::express::SchemaRegistry registry;
  std::vector<double> times;
  double mb = 0;
  double rss_after_load = 0;
  std::vector<double> first_text;
  std::size_t out_bytes = 0;
  std::size_t pieces = 0;
  ncpost::pipeline::PostOptions options;
  if (batch_bytes) options.render.batch_bytes = *batch_bytes;
  if (render_thread_min) options.render_thread_min_instances = *render_thread_min;
  const ncpost::parallel::ThreadGroup helpers(load_helpers);
  ncpost::pipeline::LoadOptions load_options;
  load_options.helpers = &helpers.helpers();
  for (int i = 0; i < runs; ++i) {
    std::string bytes = ncpost::bench::slurp(file);
    mb = static_cast<double>(bytes.size()) / 1e6;
    const auto start = Clock::now();
    auto model = ncpost::pipeline::load(std::move(bytes), registry, load_options);
    if (i == 0) rss_after_load = ncpost::bench::peak_rss_mib();
    if (!model.ok()) {
      std::cerr << "the program did not load\n";
      return 1;
    }
    out_bytes = 0;
    pieces = 0;
    const auto result = ncpost::pipeline::post(
        model, *loaded,
        [&](std::string_view s) {
          if (pieces++ == 0) first_text.push_back(seconds_since(start));
          out_bytes += s.size();
        },
        options);
    times.push_back(seconds_since(start));
    if (!result.ok) {
      print(result.diagnostics);
      std::cerr << "post failed\n";
      return 1;
    }
  }
  const Stats s = stats(times);
  const Stats f = stats(first_text);
  std::cout << "profile=" << id << " batch_bytes=" << options.render.batch_bytes
            << " render_thread_min=" << options.render_thread_min_instances
            << " load_helpers=" << load_helpers << " file_mb=" << mb << " out_bytes=" << out_bytes
            << " pieces=" << pieces << " runs=" << runs << " post_best_s=" << s.best
            << " post_median_s=" << s.median << " mb_per_s_median=" << mb / s.median
            << " mb_per_s_best=" << mb / s.best << " first_text_median_s=" << f.median
            << " peak_rss_after_load_mib=" << rss_after_load
            << " peak_rss_after_post_mib=" << ncpost::bench::peak_rss_mib() << '\n';
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const std::vector<std::string> args(argv + 1, argv + argc);
  if (args.size() == 2 && args[0] == "plain-xsl") return plain_xsl(args[1]);
  if (args.size() < 3) {
    std::cerr << "usage: render_bench plain-xsl OUT.xsl\n"
                 "       render_bench transform XSL|PROFILE XML [RUNS]\n"
                 "       render_bench cache PROFILE FILE [RUNS]\n"
                 "       render_bench pipeline PROFILE FILE [RUNS] [BATCH_BYTES] "
                 "[RENDER_THREAD_MIN] [LOAD_HELPERS]\n";
    return 2;
  }
  ncpost::xslt::initialise();
  const int runs = args.size() > 3 ? std::stoi(args[3]) : 5;
  if (args[0] == "transform") return transform(args[1], args[2], runs);
  if (args[0] == "cache") return cache(args[1], args[2], runs);
  if (args[0] == "pipeline")
    return pipeline(
        args[1], args[2], runs,
        args.size() > 4 ? std::optional<std::size_t>(std::stoull(args[4])) : std::nullopt,
        args.size() > 5 ? std::optional<std::size_t>(std::stoull(args[5])) : std::nullopt,
        args.size() > 6 ? std::stoull(args[6]) : ncpost::parallel::spare_cores());
  std::cerr << "render_bench: unknown mode " << args[0] << '\n';
  return 2;
}
