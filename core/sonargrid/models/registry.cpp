// SPDX-License-Identifier: BSD-3-Clause
#include <algorithm>
#include <atomic>
#include <stdexcept>

#include "sonargrid/models/cone_model.h"
#include "sonargrid/models/model_classes.h"
#include "sonargrid/testing/registry_hooks.h"

namespace sg {
namespace {
testing::SensorModelWrapper& modelWrapper() {
  static testing::SensorModelWrapper wrap;
  return wrap;
}
}  // namespace

void testing::wrapSensorModels(SensorModelWrapper wrap) {
  modelWrapper() = std::move(wrap);
}

namespace {
std::atomic<ConeLanes> coneLaneLimit{ConeLanes::Avx512};
}  // namespace

ConeLanes testing::limitConeLanes(ConeLanes widest) {
  return coneLaneLimit.exchange(widest);
}

ConeLanes coneLanes() {
#ifdef SG_WIDE_LANES
  static const ConeLanes cpu =
      __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
              __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq")
          ? ConeLanes::Avx512
      : __builtin_cpu_supports("avx2") ? ConeLanes::Avx2
                                       : ConeLanes::Four;
  return std::min(cpu, coneLaneLimit.load(std::memory_order_relaxed));
#else
  return ConeLanes::Four;
#endif
}

ParameterSpec noEchoParameter(const std::string& freeMeaning) {
  // Default 0: a sonar that hears nothing has most often been reflected away by a surface seen at a
  // glancing angle (paper 000 §1, "specular reflections"), and clearing its whole cone erases the
  // very walls it missed. Turn it on for diffuse surroundings.
  return ParameterSpec{
      "no_echo",
      "—",
      "",
      0.0,
      1.0,
      0.0,
      "project choice; off by default because of specular reflections (paper 000 §1)",
      "1: a reading with no echo gives " + freeMeaning + "; 0: it is skipped.",
      true};
}

std::vector<std::string> sensorModelNames() {
  return {"hpf", "konolige", "murphy", "parameterized", "himm"};
}

std::unique_ptr<SensorModel> makeSensorModel(const std::string& name) {
  std::unique_ptr<SensorModel> m;
  if (name == "hpf")
    m = makeHpfModel();
  else if (name == "konolige")
    m = makeKonoligeModel();
  else if (name == "murphy")
    m = makeMurphyModel();
  else if (name == "parameterized")
    m = makeParameterizedModel();
  else if (name == "himm")
    m = makeHimmModel();
  if (m) m->configure(ParameterSet(m->info().parameters));
  if (m && modelWrapper()) m = modelWrapper()(std::move(m));
  return m;
}

std::string sensorModelCaveat(const std::string& name) {
  if (name == "murphy")
    return "As paper 002 prints it (eqs 1-4): before the echo, cells near the cone's edges far out "
           "turn occupied, and echo cells at its corners free, the faults its section 3.2 names; "
           "expect occupied wedges.";
  if (name == "parameterized")
    return "P3 is in metres: Figure 6's P3 = 1.0 (the sensor's range units) draws a 2 m occupied "
           "band here; paper 002 Table 1's sets use 0.25 to 1.5.";
  if (name == "hpf")
    return "Writes the whole cone: walls come out a beam wide (paper 000 Table 1: IOP about 220 mm "
           "against HIMM's 86).";
  return {};
}

const ModelInfo& sensorModelInfo(const std::string& name) {
  if (name == "hpf") return hpfModelInfo();
  if (name == "konolige") return konoligeModelInfo();
  if (name == "murphy") return murphyModelInfo();
  if (name == "parameterized") return parameterizedModelInfo();
  if (name == "himm") return himmModelInfo();
  throw std::invalid_argument("unknown sensor model '" + name + "'");
}

void SensorModel::footprintRows(const Beam& beam, const GridSpec& grid, const BeamTables& tables,
                                RowWindow window, Footprint& out) const {
  const std::size_t start = out.cells.size();
  footprint(beam, grid, tables, out);
  const auto width = static_cast<std::uint32_t>(grid.width);
  auto kept = out.cells.begin() + static_cast<std::ptrdiff_t>(start);
  for (auto c = kept; c != out.cells.end(); ++c) {
    if (window.contains(static_cast<int>(c->cell / width))) *kept++ = *c;
  }
  out.cells.erase(kept, out.cells.end());
}

}  // namespace sg
