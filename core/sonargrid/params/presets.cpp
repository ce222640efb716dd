// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/params/presets.h"

namespace sg {

namespace {

// Paper 002 §4 ties P1 = 1 − P4 in every parameter set it prints (Table 1 footnote "*P1").
std::vector<PresetValue> parameterizedValues(double p1, double p2, double p3, double p4, double p5,
                                             const std::string& where) {
  return {{"p1", p1, where + " (P1 = 1 − P4)"},
          {"p2", p2, where},
          {"p3", p3, where},
          {"p4", p4, where},
          {"p5", p5, where + " (degrees)"}};
}

std::vector<Preset> buildPresets() {
  // Paper 001's experiments: its §5 table gives the multiple-target model and the log update the
  // same row (63.33 %, 13.50 %, 10.48 %, 42.7 %), so the update rules were compared on the
  // multiple-target model and the models on the log update.
  const std::vector<PresetValue> konolige001 = {
      {"false_rate", 0.05, "paper 001 §2.2 (\"for experiments, this was set to 0.05\")"},
      {"attenuation", 0.6, "paper 001 §2.2 (a(r) = 0.6 (1 − min(1, 0.4 r)))"},
      {"attenuation_slope", 0.4, "paper 001 §2.2 (a(r) = 0.6 (1 − min(1, 0.4 r)))"},
      {"range_sd0", 0.01, "paper 001 §2.2 (d(r) = 0.01 + 0.015 r)"},
      {"range_sd1", 0.015, "paper 001 §2.2 (d(r) = 0.01 + 0.015 r)"},
  };
  const std::vector<PresetValue> log001 = {
      {"cut_min", -2.0, "paper 001 §3.3 (cut-offs [−2..+2])"},
      {"cut_max", 2.0, "paper 001 §3.3 (cut-offs [−2..+2])"},
  };
  auto join = [](std::vector<PresetValue> a, const std::vector<PresetValue>& b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
  };

  return {
      {"paper000-hpf",
       "Raschke & Borenstein 1990: HPF (certainty grid, probability addition)",
       "hpf",
       "addition",
       "paper 000 §2.1 eqs 1–8; ε and ω are not printed, so they keep their defaults",
       {{"combine", 0.0, "paper 000 eqs 7–8 (Occ if Occ ≥ Emp, else −Emp)"},
        {"normalise", 0.0, "paper 000 §2.1 (probability addition; no normalisation printed)"}},
       "paper000-himm"},
      {"paper000-himm",
       "Raschke & Borenstein 1990: HIMM (histogram grid)",
       "himm",
       "himm",
       "paper 000 §2.2",
       {{"increment", 3.0, "paper 000 §2.2 (I⁺ = 3)"},
        {"decrement", 1.0, "paper 000 §2.2 (I⁻ = 1)"},
        {"cv_max", 15.0, "paper 000 §2.2 (CV_max = 15)"}},
       "paper000-hpf"},
      {"paper001-2dg-simple",
       "O'Sullivan et al.: 2-D Gaussian model, simple update",
       "hpf",
       "addition",
       "paper 001 §2.1 and §3.1",
       {{"combine", 1.0, "paper 001 §3.1 (Map = 1 − Emp if Emp > Occ, else Occ)"},
        {"normalise", 1.0, "paper 001 §3.1 (Po ← Po / ΣPo)"}},
       ""},
      {"paper001-2dg-log", "O'Sullivan et al.: 2-D Gaussian model, log update", "hpf", "log",
       "paper 001 §2.1, §3.3 and §5.1 (models compared on the log update)", log001,
       "paper001-mt-log"},
      {"paper001-mt-log", "O'Sullivan et al.: multiple-target model, log update", "konolige", "log",
       "paper 001 §2.2, §3.3 and §5", join(konolige001, log001), "paper001-2dg-log"},
      {"paper001-mt-simple", "O'Sullivan et al.: multiple-target model, simple update", "konolige",
       "addition", "paper 001 §2.2, §3.1 and §5.2",
       join(konolige001, {{"combine", 1.0, "paper 001 §3.1 (Map = 1 − Emp if Emp > Occ, else Occ)"},
                          {"normalise", 1.0, "paper 001 §3.1 (Po ← Po / ΣPo)"}}),
       ""},
      {"paper001-mt-bayes", "O'Sullivan et al.: multiple-target model, Bayesian update", "konolige",
       "bayes", "paper 001 §2.2, §3.2 and §5.2",
       join(konolige001, {{"prior", 0.5, "paper 001 §3.2 (0.5: no information about the cell)"}}),
       ""},
      {"paper002-fig3",
       "Arafat et al. Fig. 3: Murphy's model on the axis (read it at s = 5 m)",
       "murphy",
       "bayes-recursive",
       "paper 002 §3.1, Figure 3 (s = 5); R is not printed, so it keeps its default",
       {{"max_occupied", 0.9, "paper 002 Figure 3 (Max_occupied = 0.9)"},
        {"tolerance", 0.5, "paper 002 Figure 3 (Tolerance = ±0.5)"}},
       ""},
      {"paper002-fig6-standard",
       "Arafat et al. Fig. 6 left: standard (Murphy) model",
       "murphy",
       "bayes-recursive",
       "paper 002 §4, Figure 6 (left); Bayesian updating of §3.3",
       {{"beta", 15.0, "paper 002 Figure 6 (Beta = 15, degrees)"},
        {"tolerance", 1.0, "paper 002 Figure 6 (Tolerance = 1.0)"},
        {"max_occupied", 0.98, "paper 002 Figure 6 (Max_Occupied = 0.98)"}},
       "paper002-fig6-parameterized"},
      {"paper002-fig6-parameterized", "Arafat et al. Fig. 6 right: parameterized model",
       "parameterized", "bayes-recursive",
       "paper 002 §4, Figure 6 (right) and the text below it; Bayesian updating of §3.3",
       parameterizedValues(0.02, 0.15, 1.0, 0.98, 15.0, "paper 002 Figure 6"),
       "paper002-fig6-standard"},
      // Table 1 prints 2·P3; P3 is half of it.
      {"paper002-table1-histogram", "Arafat et al. Table 1: optimum by the lowest histogram bin",
       "parameterized", "bayes-recursive", "paper 002 §5, Table 1 column 5, Figure 8 (d)",
       parameterizedValues(0.03, 0.171, 0.393, 0.97, 6.14,
                           "paper 002 Table 1 col. 5 (2·P3 = 0.786)"),
       ""},
      {"paper002-table1-min-vsdns", "Arafat et al. Table 1: optimum by minimum VSDNS",
       "parameterized", "bayes-recursive", "paper 002 §5, Table 1 column 6, Figure 8 (e)",
       parameterizedValues(0.02, 0.2, 0.25, 0.98, 6.0, "paper 002 Table 1 col. 6 (2·P3 = 0.5)"),
       ""},
      {"paper002-table1-mean-vsdns", "Arafat et al. Table 1: optimum by mean VSDNS",
       "parameterized", "bayes-recursive", "paper 002 §5, Table 1 column 7, Figure 8 (f)",
       parameterizedValues(0.02, 0.05, 1.0, 0.98, 14.0, "paper 002 Table 1 col. 7 (2·P3 = 2.0)"),
       ""},
      {"paper002-fig9-derivative", "Arafat et al. Fig. 9: optimum by derivative noise",
       "parameterized", "bayes-recursive", "paper 002 §5 second approach, Figure 9",
       parameterizedValues(0.05, 0.2, 0.5, 0.95, 40.0, "paper 002 Figure 9 (P3 = 0.5 as printed)"),
       ""},
      {"paper002-fig10-two-runs", "Arafat et al. Fig. 10: optimum by two-run comparison",
       "parameterized", "bayes-recursive", "paper 002 §5 third approach, Figure 10",
       parameterizedValues(0.02, 0.05, 1.5, 0.98, 35.0, "paper 002 Figure 10 (2·P3 = 3)"), ""},
  };
}

}  // namespace

const std::vector<Preset>& paperPresets() {
  static const std::vector<Preset> presets = buildPresets();
  return presets;
}

const Preset* findPreset(const std::string& name) {
  for (const Preset& p : paperPresets()) {
    if (p.name == name) return &p;
  }
  return nullptr;
}

MapperSettings applyPreset(const Preset& preset) {
  MapperSettings s;
  s.model = preset.model;
  s.rule = preset.rule;
  try {
    s.parameters = defaultParameters(preset.model, preset.rule);
    for (const PresetValue& v : preset.values) s.parameters.set(v.parameter, v.value);
  } catch (const ParameterError& e) {
    throw ParameterError("preset '" + preset.name + "': " + e.what());
  } catch (const MapperError& e) {
    throw MapperError("preset '" + preset.name + "': " + e.what());
  }
  return s;
}

}  // namespace sg
