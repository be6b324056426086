// The classes of unsupported keywords (docs/keywords.md, "Unsupported keywords"). Exact names
// are looked up first, then the longest matching prefix; a keyword no rule names changes the
// physics. Keep this list and the table in docs/keywords.md the same.
#include "io/keyword/keyword_classes.hpp"

#include <array>

namespace rf::io {

namespace {

struct Rule {
  std::string_view name;  // exact name, or a prefix when `prefix` is set
  bool prefix;
  UnsupportedClass cls;
  std::string_view what;
};

constexpr UnsupportedClass kOutput = UnsupportedClass::OutputOnly;
constexpr UnsupportedClass kPhysics = UnsupportedClass::Physics;

// Output-only: results are the same without them; only a file or a printout is missing.
// Physics: everything else, named by family so that the message says what is lost.
constexpr std::array kRules{
    // --- output-only ---
    Rule{"*DATABASE_", true, kOutput, "an output request"},
    Rule{"*CONTROL_ENERGY", false, kOutput, "energy bookkeeping options for output"},
    Rule{"*CONTROL_OUTPUT", false, kOutput, "output options"},
    Rule{"*CONTROL_MPP_IO_", true, kOutput, "MPP output options"},
    Rule{"*CONTROL_MPP_DECOMPOSITION_", true, kOutput,
         "an MPP domain decomposition (no effect on a shared-memory run)"},
    Rule{"*CONTROL_CPU", false, kOutput, "a CPU-time limit"},
    Rule{"*CONTROL_PARALLEL", false, kOutput, "parallel-execution options"},
    Rule{"*INTERFACE_SPRINGBACK_", true, kOutput, "a springback output file"},
    // --- physics, by family ---
    Rule{"*LOAD_", true, kPhysics, "a load"},
    Rule{"*LOAD_THERMAL_", true, kPhysics, "a thermal load"},
    Rule{"*BOUNDARY_", true, kPhysics, "a boundary condition"},
    Rule{"*BOUNDARY_THERMAL_", true, kPhysics, "a thermal boundary condition"},
    Rule{"*CONSTRAINED_", true, kPhysics, "a constraint"},
    Rule{"*CONSTRAINED_JOINT_STIFFNESS", true, kPhysics,
         "a joint stiffness variant that is not supported (supported: "
         "*CONSTRAINED_JOINT_STIFFNESS_GENERALIZED; _TRANSLATIONAL, _FLEXION-TORSION, "
         "_CYLINDRICAL and _SPHERICAL are not)"},
    Rule{"*CONTROL_", true, kPhysics, "a solver control"},
    Rule{"*CONTROL_THERMAL_", true, kPhysics, "a thermal solver control"},
    Rule{"*CONTROL_ALE", true, kPhysics, "an ALE control"},
    Rule{"*CONTROL_SPH", true, kPhysics, "an SPH control"},
    Rule{"*MAT_", true, kPhysics, "a material"},
    Rule{"*MAT_THERMAL_", true, kPhysics, "a thermal material"},
    Rule{"*EOS", true, kPhysics, "an equation of state"},
    Rule{"*SECTION_", true, kPhysics, "a section (element formulation)"},
    Rule{"*SECTION_SHELL", true, kPhysics,
         "a shell section variant that is not supported (supported: *SECTION_SHELL(_TITLE))"},
    Rule{"*SECTION_BEAM", true, kPhysics,
         "a beam section variant that is not supported (supported: *SECTION_BEAM(_TITLE))"},
    Rule{"*SECTION_TSHELL", true, kPhysics,
         "a thick-shell section: thick shells are not supported yet"},
    Rule{"*SECTION_DISCRETE", true, kPhysics,
         "a discrete-element section variant that is not supported (supported: "
         "*SECTION_DISCRETE(_TITLE))"},
    Rule{"*SECTION_SPH", true, kPhysics, "an SPH section"},
    Rule{"*ELEMENT_", true, kPhysics, "an element keyword"},
    Rule{"*ELEMENT_SHELL", true, kPhysics,
         "a shell element variant that is not supported (supported: *ELEMENT_SHELL, "
         "_THICKNESS, _BETA, _MCID)"},
    Rule{"*ELEMENT_BEAM", true, kPhysics,
         "a beam element variant that is not supported (supported: *ELEMENT_BEAM, "
         "_ORIENTATION)"},
    Rule{"*ELEMENT_TSHELL", true, kPhysics, "thick-shell elements: not supported yet"},
    Rule{"*ELEMENT_DISCRETE", true, kPhysics,
         "a discrete element variant that is not supported (supported: *ELEMENT_DISCRETE)"},
    Rule{"*ELEMENT_MASS", true, kPhysics, "point masses: not supported yet"},
    Rule{"*ELEMENT_SPH", true, kPhysics, "SPH particles"},
    Rule{"*PART", true, kPhysics, "a part definition"},
    Rule{"*NODE", true, kPhysics, "a node definition"},
    Rule{"*INITIAL_", true, kPhysics, "an initial condition"},
    Rule{"*INITIAL_TEMPERATURE", true, kPhysics, "an initial temperature (thermal)"},
    Rule{"*CONTACT_", true, kPhysics, "a contact"},
    Rule{"*RIGIDWALL_", true, kPhysics, "a rigid wall"},
    Rule{"*RIGID_", true, kPhysics, "a rigid-body option"},
    Rule{"*DEFORMABLE_TO_RIGID", true, kPhysics, "a part switch"},
    Rule{"*DAMPING_", true, kPhysics, "damping"},
    Rule{"*HOURGLASS", true, kPhysics, "hourglass control"},
    Rule{"*ALE_", true, kPhysics, "ALE"},
    Rule{"*SPH_", true, kPhysics, "SPH"},
    Rule{"*ICFD_", true, kPhysics, "incompressible CFD (ICFD)"},
    Rule{"*EM_", true, kPhysics, "electromagnetics (EM)"},
    Rule{"*CESE_", true, kPhysics, "compressible CFD (CESE)"},
    Rule{"*DUALCESE_", true, kPhysics, "compressible CFD (DUALCESE)"},
    Rule{"*THERMAL", true, kPhysics, "thermal analysis"},
    Rule{"*AIRBAG_", true, kPhysics, "an airbag"},
    Rule{"*CASE", true, kPhysics,
         "a load case: each *CASE is a separate analysis, and merging their contents would run "
         "a different model"},
    Rule{"*DEFINE_", true, kPhysics, "a definition other keywords use"},
    Rule{"*SET_", true, kPhysics, "a set"},
    Rule{"*SET_SHELL", true, kPhysics,
         "a shell set of a form not supported (only *SET_SHELL(_LIST))"},
    Rule{"*SET_BEAM", true, kPhysics, "a beam set of a form not supported (only *SET_BEAM)"},
    Rule{"*SENSOR_", true, kPhysics, "a sensor"},
    Rule{"*INCLUDE_", true, kPhysics, "an include variant (its data would be missing)"},
    Rule{"*PARAMETER_", true, kPhysics, "a parameter variant"},
    Rule{"*TERMINATION_", true, kPhysics, "a termination condition"},
    Rule{"*PERTURBATION_", true, kPhysics, "a geometry or property perturbation"},
    Rule{"*USER_", true, kPhysics, "a user subroutine"},
    Rule{"*MESH_", true, kPhysics, "a generated mesh"},
    Rule{"*FREQUENCY_DOMAIN_", true, kPhysics, "a frequency-domain analysis"},
};

}  // namespace

UnsupportedKind classify_unsupported(std::string_view keyword) {
  const Rule* best = nullptr;
  for (const Rule& rule : kRules) {
    if (best && !best->prefix) break;  // an exact name wins
    if (!rule.prefix) {
      // An exact name, also with the _TITLE or _ID option (*CONTROL_OUTPUT_TITLE); any other
      // suffix makes another keyword, unknown to this rule.
      const std::string_view rest =
          keyword.starts_with(rule.name) ? keyword.substr(rule.name.size()) : "?";
      if (rest.empty() || rest == "_TITLE" || rest == "_ID") best = &rule;
      continue;
    }
    if (!keyword.starts_with(rule.name)) continue;
    if (best && !best->prefix) continue;
    if (!best || rule.name.size() > best->name.size()) best = &rule;
  }
  if (!best) return {UnsupportedClass::Physics, "an unknown keyword"};
  return {best->cls, best->what};
}

}  // namespace rf::io
