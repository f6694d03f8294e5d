// SPDX-License-Identifier: BSD-3-Clause
// csm-analyze: the analytic planner. For a view frustum and a light angle it prints the split
// depths, warp parameters and perspective aliasing error (Lloyd et al. 2006) of each cascade.
// With --partition face it prints the face partitions (Lloyd et al. 2006, §5.1) instead: one warped
// map per side face the light enters, z-partitioned along the face with --cascades K (FP+ZP+W;
// a comparison technique, in a build with CSM_COMPARISON_TECHNIQUES).
// With --table it prints a speed-against-error table for a CAD-like configuration.
#include "csmAtlas.h"
#include "csmCascadeCount.h"
#include "csmSetup.h"
#if CSM_COMPARISON_TECHNIQUES
#include "csmFacePartition.h"
#endif

#include <glm/geometric.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace
{
constexpr double kPi = 3.14159265358979323846;

struct Options
{
  double near = 1.0;
  double far = 100.0;
  double fovy = 60.0;
  double gamma = 90.0;
  double aspect = 1.0;
  csm::Settings settings;
  bool json = false;
  bool table = false;
  bool face = false;        ///< --partition face: face partitioning instead of z-partitioning alone
  double errorTarget = 0.0; ///< > 0: the cascade count from the error model, up to --cascades
  double imageHeight = 600.0;
  int resolution = 2048;
};

[[noreturn]] void fail(const std::string& message)
{
  std::fprintf(stderr, "csm-analyze: error: %s (see --help)\n", message.c_str());
  std::exit(2);
}

void usage()
{
  std::printf(
    "usage: csm-analyze [options]\n"
    "  --near N          camera near distance, >= 1e-50        [1]\n"
    "  --far F           camera far distance, > near, <= 1e50  [100]\n"
    "  --fovy DEG        vertical field of view, (0, 180)      [60]\n"
    "  --aspect A        image width / height (> 0)            [1]\n"
    "  --gamma DEG       angle between light and view, [0, 180]: 0 light from behind,\n"
    "                    90 perpendicular, 180 facing the viewer [90]\n"
    "  --warp MODE       none | psm | lispsm | generalized     [generalized]\n"
#if CSM_COMPARISON_TECHNIQUES
    "  --partition S     single | uniform | log | practical | adaptive | face [adaptive]\n"
    "                    face: one map per side face of the view frustum the light enters\n"
    "                    (Lloyd et al. 2006, 5.1), each z-partitioned into K log partitions\n"
    "  --cascades K      number of partitions (>= 1), per face with --partition face [2]\n"
#else
    "  --partition S     single | uniform | log | practical | adaptive [adaptive]\n"
    "  --cascades K      number of partitions (>= 1) [2]\n"
#endif
    "  --alpha A         adaptive: far partitions' f/n at gamma 0 (> 1) [2]\n"
    "  --lambda L        practical: weight of the log splits, [0, 1] [0.5]\n"
    "  --error-target M  > 0: the number of cascades from the error model, as the pass's\n"
    "                    AdaptiveCascades chooses it: the fewest, up to --cascades, whose\n"
    "                    predicted worst error m (texels a pixel) is at most M [off]\n"
    "  --image-height H  pixels, for --error-target [600]\n"
    "  --resolution R    largest map side in texels, for --error-target [2048]\n"
    "  --json            print one JSON object instead of a table\n"
    "  --table           speed-against-error table of common settings for a CAD-like view\n"
    "                    (near 0.5, far 5000, fovy 45, 4:3)\n");
}

double number(const char* flag, const char* text)
{
  if (!text)
  {
    fail(std::string(flag) + " needs a value");
  }
  char* end = nullptr;
  const double value = std::strtod(text, &end);
  if (end == text || *end != '\0' || !std::isfinite(value))
  {
    fail(std::string(flag) + " needs a finite number, got '" + text + "'");
  }
  return value;
}

Options parse(int argc, char** argv)
{
  Options o;
  for (int i = 1; i < argc; ++i)
  {
    const std::string flag = argv[i];
    const char* value = i + 1 < argc ? argv[i + 1] : nullptr;
    if (flag == "--help" || flag == "-h")
    {
      usage();
      std::exit(0);
    }
    else if (flag == "--json")
      o.json = true;
    else if (flag == "--table")
      o.table = true;
    else if (flag == "--near")
      o.near = number(argv[i++], value);
    else if (flag == "--far")
      o.far = number(argv[i++], value);
    else if (flag == "--fovy")
      o.fovy = number(argv[i++], value);
    else if (flag == "--aspect")
      o.aspect = number(argv[i++], value);
    else if (flag == "--gamma")
      o.gamma = number(argv[i++], value);
    else if (flag == "--alpha")
      o.settings.split.alpha = number(argv[i++], value);
    else if (flag == "--lambda")
      o.settings.split.lambda = number(argv[i++], value);
    else if (flag == "--error-target")
    {
      o.errorTarget = number(argv[i++], value);
      if (!(o.errorTarget > 0.0))
        fail("--error-target must be > 0");
    }
    else if (flag == "--image-height")
    {
      o.imageHeight = number(argv[i++], value);
      if (!(o.imageHeight >= 1.0 && o.imageHeight <= 1e5))
        fail("--image-height must be in [1, 100000]");
    }
    else if (flag == "--resolution")
    {
      const double r = number(argv[i++], value);
      if (r != std::floor(r) || r < 64 || r > 16384)
        fail("--resolution needs a whole number in [64, 16384]");
      o.resolution = static_cast<int>(r);
    }
    else if (flag == "--cascades")
    {
      const double k = number(argv[i++], value);
      if (k != std::floor(k) || k < 1 || k > csm::kMaxSplits)
        fail("--cascades needs a whole number in [1, " + std::to_string(csm::kMaxSplits) + "]");
      o.settings.split.k = static_cast<int>(k);
    }
    else if (flag == "--warp")
    {
      if (!csm::parseWarpMode(value, o.settings.warp))
        fail("--warp must be one of none, psm, lispsm, generalized");
      ++i;
    }
    else if (flag == "--partition")
    {
      o.face = value && std::strcmp(value, "face") == 0;
#if !CSM_COMPARISON_TECHNIQUES
      if (o.face)
        fail("--partition face: this build has no comparison techniques (configure with "
             "-DCSM_COMPARISON_TECHNIQUES=ON)");
#endif
      if (!o.face && !csm::parseSplitScheme(value, o.settings.split.scheme))
        fail("--partition must be one of single, uniform, log, practical, adaptive" +
          std::string(CSM_COMPARISON_TECHNIQUES ? ", face" : ""));
      ++i;
    }
    else
      fail("unknown option '" + flag + "'");
  }
  if (!(o.near > 0.0))
    fail("--near must be > 0");
  if (!(o.far > o.near))
    fail("--far must be greater than --near");
  if (!(o.fovy > 0.0 && o.fovy < 180.0))
    fail("--fovy must be in (0, 180)");
  if (!(o.aspect > 0.0))
    fail("--aspect must be > 0");
  if (!(o.gamma >= 0.0 && o.gamma <= 180.0))
    fail("--gamma must be in [0, 180]");
  if (!(o.settings.split.alpha > 1.0))
    fail("--alpha must be > 1");
  if (!(o.settings.split.lambda >= 0.0 && o.settings.split.lambda <= 1.0))
    fail("--lambda must be in [0, 1]");
  if (o.errorTarget > 0.0 && (o.face || o.table))
    fail("--error-target chooses a number of z-partitions: not with --partition face or --table");
  if (o.json && o.table)
    fail("--table prints a table only: not with --json");
  return o;
}

// Eye at the origin looking down -z with +y up; the light in the plane of view and up vectors.
csm::Camera makeCamera(const Options& o)
{
  csm::Camera c;
  c.vsNear = o.near;
  c.vsFar = o.far;
  c.fovyDeg = o.fovy;
  c.aspect = o.aspect;
  return c;
}

glm::dvec3 lightDirection(double gammaDeg)
{
  const double g = gammaDeg * kPi / 180.0;
  return { 0.0, -std::sin(g), -std::cos(g) }; // cos(g) view - sin(g) up
}

std::string jsonNumber(double value)
{
  if (!std::isfinite(value))
    return "null";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.17g", value);
  return buffer;
}

void printJson(const Options& o, const csm::ShadowSetup& s)
{
  std::printf("{\"inputs\": {\"near\": %s, \"far\": %s, \"fovy\": %s, \"aspect\": %s, "
              "\"gamma\": %s, \"warp\": \"%s\", \"partition\": \"%s\", \"cascades\": %d, "
              "\"alpha\": %s, \"lambda\": %s},\n",
    jsonNumber(o.near).c_str(), jsonNumber(o.far).c_str(), jsonNumber(o.fovy).c_str(),
    jsonNumber(o.aspect).c_str(), jsonNumber(o.gamma).c_str(), csm::toString(o.settings.warp),
    csm::toString(o.settings.split.scheme), o.settings.split.k,
    jsonNumber(o.settings.split.alpha).c_str(), jsonNumber(o.settings.split.lambda).c_str());
  std::printf(" \"status\": \"%s\", \"gamma_lim_deg\": %s,\n \"cascades\": [",
    csm::toString(s.status), jsonNumber(s.gammaLimDeg).c_str());
  for (size_t i = 0; i < s.cascades.size(); ++i)
  {
    const csm::Cascade& c = s.cascades[i];
    std::printf("%s\n  {\"near\": %s, \"far\": %s, \"n_prime\": %s, \"gamma_lim_deg\": %s, "
                "\"Mx\": %s, \"Mz\": %s, \"storage\": %s}",
      i ? "," : "", jsonNumber(c.vsNear).c_str(), jsonNumber(c.vsFar).c_str(),
      jsonNumber(c.nPrime).c_str(), jsonNumber(c.gammaLimDeg).c_str(), jsonNumber(c.Mx).c_str(),
      jsonNumber(c.Mz).c_str(), jsonNumber(c.storage).c_str());
  }
  std::printf("],\n \"storage_total\": %s, \"storage_optimal\": %s",
    jsonNumber(s.storageTotal).c_str(), jsonNumber(s.storageOptimal).c_str());
  if (o.errorTarget > 0.0)
  {
    const int k = static_cast<int>(s.cascades.size());
    const csm::MapSize r = csm::resolutionCeilingForCount(k, o.settings.split.k, o.resolution);
    std::printf(",\n \"error_target\": %s, \"chosen_cascades\": %d, \"resolution\": [%d, %d], "
                "\"predicted_error\": %s",
      jsonNumber(o.errorTarget).c_str(), k, r.width, r.height,
      jsonNumber(csm::predictedError(s, o.imageHeight, r)).c_str());
  }
  std::printf("}\n");
}

void printText(const Options& o, const csm::ShadowSetup& s)
{
  std::printf("view: near %g far %g (f/n %g), fovy %g deg, aspect %g; light at gamma %g deg\n",
    o.near, o.far, o.far / o.near, o.fovy, o.aspect, o.gamma);
  std::printf("warp %s, partition %s, k %d, alpha %g, lambda %g; gamma_lim %.4f deg\n",
    csm::toString(o.settings.warp), csm::toString(o.settings.split.scheme), o.settings.split.k,
    o.settings.split.alpha, o.settings.split.lambda, s.gammaLimDeg);
  std::printf(
    "%-3s %14s %14s %14s %12s %12s %12s\n", "i", "near", "far", "n'", "Mx", "Mz", "storage");
  for (size_t i = 0; i < s.cascades.size(); ++i)
  {
    const csm::Cascade& c = s.cascades[i];
    char np[32];
    if (std::isfinite(c.nPrime))
      std::snprintf(np, sizeof np, "%14.6g", c.nPrime);
    else
      std::snprintf(np, sizeof np, "%14s", "inf (ortho)");
    std::printf("%-3zu %14.6g %14.6g %s %12.5g %12.5g %12.5g\n", i, c.vsNear, c.vsFar, np, c.Mx,
      c.Mz, c.storage);
  }
  std::printf("storage total %.6g, optimal %.6g (ratio %.3g)\n", s.storageTotal, s.storageOptimal,
    s.storageTotal / s.storageOptimal);
  if (o.errorTarget > 0.0)
  {
    // The choice as AdaptiveCascades makes it, and every count's own plan beside it.
    std::printf("error target %g at %g pixels, maps of at most %d texels: %zu cascade(s) "
                "chosen of up to %d\n",
      o.errorTarget, o.imageHeight, o.resolution, s.cascades.size(), o.settings.split.k);
    std::printf("%-3s %12s %16s\n", "k", "texels", "predicted m");
    for (int k = 1; k <= o.settings.split.k; ++k)
    {
      const csm::ShadowSetup plan =
        csm::computeShadowSetupForCount(makeCamera(o), lightDirection(o.gamma), nullptr, o.settings,
          nullptr, k, csm::resolutionCeilingForCount(k, o.settings.split.k, o.resolution));
      const csm::MapSize r = csm::resolutionCeilingForCount(
        static_cast<int>(plan.cascades.size()), o.settings.split.k, o.resolution);
      const std::string texels = std::to_string(r.width) + "x" + std::to_string(r.height);
      std::printf("%-3zu %12s %16.4g%s\n", plan.cascades.size(), texels.c_str(),
        csm::predictedError(plan, o.imageHeight, r),
        plan.cascades.size() == s.cascades.size() ? "   <- chosen" : "");
    }
  }
}

#if CSM_COMPARISON_TECHNIQUES
void printFaceJson(const Options& o, const csm::FacePartitioning& s)
{
  std::printf("{\"inputs\": {\"near\": %s, \"far\": %s, \"fovy\": %s, \"aspect\": %s, "
              "\"gamma\": %s, \"warp\": \"%s\", \"partition\": \"face\", \"cascades\": %d},\n",
    jsonNumber(o.near).c_str(), jsonNumber(o.far).c_str(), jsonNumber(o.fovy).c_str(),
    jsonNumber(o.aspect).c_str(), jsonNumber(o.gamma).c_str(), csm::toString(o.settings.warp),
    o.settings.split.k);
  std::printf(" \"status\": \"%s\",\n \"partitions\": [", csm::toString(s.status));
  for (size_t i = 0; i < s.partitions.size(); ++i)
  {
    const csm::FacePartition& p = s.partitions[i];
    const csm::Cascade& c = p.map;
    std::printf("%s\n  {\"face\": \"%s\", \"z_index\": %d, \"near\": %s, \"far\": %s, "
                "\"n_prime\": %s, \"Mx\": %s, \"Mz\": %s, \"storage\": %s}",
      i ? "," : "", csm::toString(p.face), p.zIndex, jsonNumber(c.vsNear).c_str(),
      jsonNumber(c.vsFar).c_str(), jsonNumber(c.nPrime).c_str(), jsonNumber(c.Mx).c_str(),
      jsonNumber(c.Mz).c_str(), jsonNumber(c.storage).c_str());
  }
  std::printf("],\n \"storage_total\": %s, \"storage_optimal\": %s}\n",
    jsonNumber(s.storageTotal).c_str(), jsonNumber(s.storageOptimal).c_str());
}

void printFaceText(const Options& o, const csm::FacePartitioning& s)
{
  std::printf("view: near %g far %g (f/n %g), fovy %g deg, aspect %g; light at gamma %g deg\n",
    o.near, o.far, o.far / o.near, o.fovy, o.aspect, o.gamma);
  std::printf("face partitioning (Lloyd et al. 2006, 5.1), warp %s, %d log partition(s) per face; "
              "%zu maps\n",
    csm::toString(o.settings.warp), o.settings.split.k, s.partitions.size());
  std::printf("%-7s %-3s %14s %14s %14s %12s %12s %12s\n", "face", "i", "near", "far", "n'", "Mx",
    "Mz", "storage");
  for (const csm::FacePartition& p : s.partitions)
  {
    const csm::Cascade& c = p.map;
    char np[32];
    if (std::isfinite(c.nPrime))
      std::snprintf(np, sizeof np, "%14.6g", c.nPrime);
    else
      std::snprintf(np, sizeof np, "%14s", "inf (ortho)");
    std::printf("%-7s %-3d %14.6g %14.6g %s %12.5g %12.5g %12.5g\n", csm::toString(p.face),
      p.zIndex, c.vsNear, c.vsFar, np, c.Mx, c.Mz, c.storage);
  }
  std::printf("storage total %.6g, optimal %.6g (ratio %.3g)\n", s.storageTotal, s.storageOptimal,
    s.storageTotal / s.storageOptimal);
}
#endif

// Speed against error for common settings: maps rendered per frame (the cost on the GPU), the
// time of the math per frame, and the storage factor S (critical texels / image pixels) over
// light angles. Lower S is better; S_opt is the logarithmic optimum.
void printTable()
{
  Options o;
  o.near = 0.5;
  o.far = 5000.0;
  o.fovy = 45.0;
  o.aspect = 4.0 / 3.0;
  struct Row
  {
    const char* name;
    csm::WarpMode warp;
    csm::SplitScheme scheme;
    int k;
  };
  const Row rows[] = {
    { "uniform (VTK-like)", csm::WarpMode::None, csm::SplitScheme::Single, 1 },
    { "LiSPSM", csm::WarpMode::LiSPSM, csm::SplitScheme::Single, 1 },
    { "generalized", csm::WarpMode::Generalized, csm::SplitScheme::Single, 1 },
    { "PSSM practical", csm::WarpMode::None, csm::SplitScheme::Practical, 4 },
    { "log + LiSPSM", csm::WarpMode::LiSPSM, csm::SplitScheme::Log, 4 },
    { "generalized + adaptive", csm::WarpMode::Generalized, csm::SplitScheme::Adaptive, 2 },
    { "generalized + adaptive", csm::WarpMode::Generalized, csm::SplitScheme::Adaptive, 3 },
    { "generalized + adaptive", csm::WarpMode::Generalized, csm::SplitScheme::Adaptive, 4 },
  };
  const double gammas[] = { 0.0, 10.0, 30.0, 60.0, 90.0 };
  const csm::Camera cam = makeCamera(o);
  std::printf("CAD-like view: near %g, far %g (f/n %g), fovy %g deg, aspect 4:3\n", o.near, o.far,
    o.far / o.near, o.fovy);
  std::printf("storage factor S = critical shadow-map texels / image pixels (Lloyd Eq. 12), "
              "lower is better\n");
  std::printf("%-24s %5s %9s", "technique", "maps", "math_us");
  for (double g : gammas)
    std::printf("   S@%3.0fdeg", g);
  std::printf("\n");
  double optimal = 0.0;
  for (const Row& row : rows)
  {
    csm::Settings settings;
    settings.warp = row.warp;
    settings.split.scheme = row.scheme;
    settings.split.k = row.k;
    // Median time of the per-frame math over repeated runs.
    std::vector<double> times;
    double sink = 0.0;
    for (int run = 0; run < 101; ++run)
    {
      const auto start = std::chrono::steady_clock::now();
      const csm::ShadowSetup s =
        csm::computeShadowSetup(cam, lightDirection(45.0), nullptr, settings);
      const auto stop = std::chrono::steady_clock::now();
      sink += s.storageTotal;
      times.push_back(std::chrono::duration<double, std::micro>(stop - start).count());
    }
    std::nth_element(times.begin(), times.begin() + times.size() / 2, times.end());
    std::printf("%-24s %5d %9.2f", row.name, row.k, times[times.size() / 2] + 0.0 * sink);
    for (double g : gammas)
    {
      const csm::ShadowSetup s = csm::computeShadowSetup(cam, lightDirection(g), nullptr, settings);
      optimal = s.storageOptimal;
      std::printf(" %11.4g", s.storageTotal);
    }
    std::printf("\n");
  }
  std::printf("%-24s %5s %9s %11.4g   (Lloyd App. C, one logarithmic map, overhead light)\n",
    "S_opt", "", "", optimal);
}
} // namespace

int main(int argc, char** argv)
{
  const Options o = parse(argc, argv);
  if (o.table)
  {
    printTable();
    return 0;
  }
#if CSM_COMPARISON_TECHNIQUES
  if (o.face)
  {
    csm::FacePartitionSettings settings;
    settings.warp = o.settings.warp;
    settings.k = o.settings.split.k;
    const csm::FacePartitioning s =
      csm::computeFacePartitions(makeCamera(o), lightDirection(o.gamma), settings);
    if (s.status != csm::Status::Ok)
      fail(s.message);
    if (o.json)
      printFaceJson(o, s);
    else
      printFaceText(o, s);
    return 0;
  }
#endif
  const csm::ShadowSetup s = o.errorTarget > 0.0
    ? csm::computeShadowSetupForError(makeCamera(o), lightDirection(o.gamma), nullptr, o.settings,
        nullptr, o.imageHeight, o.resolution, o.errorTarget, 0)
    : csm::computeShadowSetup(makeCamera(o), lightDirection(o.gamma), nullptr, o.settings);
  if (s.status == csm::Status::InvalidInput)
    fail(s.message);
  if (o.json)
    printJson(o, s);
  else
    printText(o, s);
  return 0;
}
