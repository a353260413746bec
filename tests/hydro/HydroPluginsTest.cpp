// The three hydro plugins load through the real plugin loader, take their default parameters and
// give the isolated-sphere mobility each is defined by.
#include <gtest/gtest.h>

#include "HydroTestSupport.hpp"
#include "fldsim-sdk/lubrication/ResistanceModel.hpp"
#include "fldsim/hydro.hpp"
#include "plugins/PluginRegistry.hpp"

using namespace fldsim;
using namespace fldsim::hydro::test;

namespace {

Params defaults(const PluginInfo& info) {
  Params p(info.kind, "test");
  for (const auto& spec : info.schema.specs())
    if (spec.default_value)
      p.set(spec.name, *spec.default_value, ParamOrigin{"test", info.kind + "." + spec.name},
            /*given=*/false);
  return p;
}

}  // namespace

TEST(HydroPlugins, LoadAndGiveTheirIsolatedSphereMobility) {
  const PluginRegistry registry({FLDSIM_TEST_PLUGIN_DIR});
  // Translational resistance of one isolated unit sphere, in units of 6 pi mu a: 1 for
  // free_draining and lubrication; for fld its default R_0 fit (smooth taper) at phi = 0.3,
  // 1 + 0.3788 phi + 1.9794 phi^2 - 10.506 phi^3 (docs/fld-r0-fit.md).
  const std::pair<const char*, double> expected[] = {
      {"free_draining", 1.0},
      {"lubrication", 1.0},
      {"fld", 1.0 + 0.3788 * 0.3 + 1.9794 * 0.09 - 10.506 * 0.027}};
  for (const auto& [name, resistance] : expected) {
    SCOPED_TRACE(name);
    const auto model = registry.create<HydroModel>("hydro", name, defaults(registry.find("hydro", name)));
    System s(sphere_shape(), 1, 20.0, physics(0.0, 0.0, 0.3));
    HydroRequest req;
    req.brownian = false;
    req.shear = false;
    const auto skipped = model->configure(s, req);
    EXPECT_EQ(skipped.size(), 3u);  // no Brownian forces, no R_FE:E, no stresslets
    model->assemble(s, NodePairList{});
    const double F[6] = {1, 0, 0, 0, 0, 0};
    double dU[6] = {0};
    model->solve(s, F, dU);
    EXPECT_NEAR(1.0 / dU[0], resistance, 1e-12);
  }
}

TEST(HydroPlugins, LammpsConventionsPresetThePairFormsAndRefuseContradictions) {
  const PluginRegistry registry({FLDSIM_TEST_PLUGIN_DIR});
  for (const char* name : {"fld", "lubrication"}) {
    SCOPED_TRACE(name);
    Params p = defaults(registry.find("hydro", name));
    p.set("conventions", std::string("lammps"), ParamOrigin{"test:3:5", "hydro.conventions"});
    const auto lammps = hydro::read_lubrication_params(p);
    EXPECT_EQ(lammps.lub.pump, hydro::PumpForm::Lammps);
    EXPECT_FALSE(lammps.lub.twist);
    EXPECT_EQ(lammps.lub.lever, hydro::Lever::Contact);
    EXPECT_EQ(lammps.lub.strain_arm, hydro::StrainArm::Contact);
    EXPECT_EQ(lammps.lub.taper_width, 0.0);
    // A key the user wrote that contradicts the preset is a configuration error naming it.
    p.set("lever", std::string("centre"), ParamOrigin{"test:4:5", "hydro.lever"});
    try {
      hydro::read_lubrication_params(p);
      ADD_FAILURE() << "conventions: lammps with lever: centre was accepted";
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find("hydro.lever"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("contradicts conventions: lammps"), std::string::npos) << e.what();
    }
    // The same value as the preset is fine.
    p.set("lever", std::string("contact"), ParamOrigin{"test:4:5", "hydro.lever"});
    EXPECT_NO_THROW(hydro::read_lubrication_params(p));
  }
}

// A loaded plugin's run-log lines reach the core through the guard that wraps every plugin object
// (PluginBoundary.hpp): the lubricated models note a preconditioner breakdown, met here as a
// resumed run could meet it (a checkpoint whose matrix is the 4-cycle on which IC(0) breaks down,
// in every numbering; ResistanceModelNotes checks which numberings and the exact lines), and a
// plugin without RunNotes is asked for none. Fails if a guard does not forward take_notes().
TEST(HydroPlugins, RunNotesPassTheGuard) {
  const PluginRegistry registry({FLDSIM_TEST_PLUGIN_DIR});
  for (const char* name : {"fld", "lubrication"}) {
    SCOPED_TRACE(name);
    const auto model = registry.create<HydroModel>("hydro", name, defaults(registry.find("hydro", name)));
    RunNotes* notes = run_notes_of(*model);
    ASSERT_NE(notes, nullptr);
    const System s = four_sphere_chain();
    model->configure(s, HydroRequest{});
    EXPECT_TRUE(notes->take_notes().empty());
    std::array<std::uint32_t, 4> label = {0, 1, 2, 3};
    int noted = 0;
    do {
      model->restore_state(four_cycle_checkpoint(label));
      for (const std::string& line : notes->take_notes()) {
        ++noted;
        EXPECT_TRUE(line.rfind("incomplete_cholesky preconditioner ", 0) == 0) << line;
      }
    } while (std::next_permutation(label.begin(), label.end()));
    EXPECT_GT(noted, 0);
  }
  const auto force =
      registry.create<ForceLaw>("force", "repulsion", defaults(registry.find("force", "repulsion")));
  ASSERT_NE(run_notes_of(*force), nullptr);
  EXPECT_TRUE(run_notes_of(*force)->take_notes().empty());
}
