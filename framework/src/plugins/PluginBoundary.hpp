// The boundary between the core and a plugin's code. Every call into a plugin object goes
// through a guard (one per plugin interface) that catches whatever the plugin throws, of any
// type, and throws instead a core exception that names the plugin and its library file. The
// plugin's own exception object is destroyed inside the guard, while its library is surely
// loaded: none can outlive the code that made it (its destructor and what() live there).
#pragma once

#include <memory>
#include <string>
#include <type_traits>
#include <utility>

#include "fldsim/error.hpp"
#include "fldsim/force.hpp"
#include "fldsim/hydro.hpp"
#include "fldsim/observer.hpp"
#include "fldsim/shape.hpp"

namespace fldsim {

// Call from inside a catch block. ConfigError keeps its text (it already names file:line:col
// and key); fldsim::Error becomes Error("<who>: <message>"); anything else Error("<who>: <call>
// threw <type>: <what>"). `who` is e.g. "observer plugin 'stress' (/path/libstress.so)".
[[noreturn]] void rethrow_from_plugin(const std::string& who, const char* call);

template <class Fn>
decltype(auto) plugin_call(const std::string& who, const char* call, Fn&& fn) {
  try {
    return fn();
  } catch (...) {
    rethrow_from_plugin(who, call);
  }
}

// A plugin object's run-log lines (RunNotes, API 5.3) through its guard, so that run_notes_of()
// finds them on the guard; none when the object has no RunNotes (a plugin of API 5.2 or older).
class GuardedNotes : public RunNotes {
 public:
  GuardedNotes(RunNotes* inner, std::string who) : notes_(inner), notes_who_(std::move(who)) {}
  std::vector<std::string> take_notes() override {
    if (!notes_) return {};
    return plugin_call(notes_who_, "take_notes()", [&] { return notes_->take_notes(); });
  }

 private:
  RunNotes* notes_;  // the inner object (kept alive by the guard), or null
  std::string notes_who_;
};

class GuardedShape final : public Shape {
 public:
  GuardedShape(std::shared_ptr<Shape> inner, std::string who) : in_(std::move(inner)), who_(std::move(who)) {}
  const std::vector<Node>& nodes() const override {
    return plugin_call(who_, "nodes()", [&]() -> const std::vector<Node>& { return in_->nodes(); });
  }
  double volume() const override {
    return plugin_call(who_, "volume()", [&] { return in_->volume(); });
  }
  Vec3 director() const override {
    return plugin_call(who_, "director()", [&] { return in_->director(); });
  }
  bool anisotropic() const override {
    return plugin_call(who_, "anisotropic()", [&] { return in_->anisotropic(); });
  }

 private:
  std::shared_ptr<Shape> in_;
  std::string who_;
};

class GuardedHydro final : public HydroModel, public GuardedNotes {
 public:
  GuardedHydro(std::shared_ptr<HydroModel> inner, std::string who)
      : GuardedNotes(run_notes_of(*inner), who), in_(std::move(inner)), who_(std::move(who)) {}
  double pair_range(const System& s) const override {
    return plugin_call(who_, "pair_range()", [&] { return in_->pair_range(s); });
  }
  std::vector<std::string> configure(const System& s, const HydroRequest& r) override {
    return plugin_call(who_, "configure()", [&] { return in_->configure(s, r); });
  }
  void assemble(const System& s, const NodePairList& p) override {
    plugin_call(who_, "assemble()", [&] { in_->assemble(s, p); });
  }
  void brownian_force(const System& s, const NodePairList& p, const RandomStream& noise, double dt,
                      double* FB) override {
    plugin_call(who_, "brownian_force()", [&] { in_->brownian_force(s, p, noise, dt, FB); });
  }
  void solve(const System& s, const double* F, double* dU) override {
    plugin_call(who_, "solve()", [&] { in_->solve(s, F, dU); });
  }
  SolveStats last_solve() const override {
    return plugin_call(who_, "last_solve()", [&] { return in_->last_solve(); });
  }
  bool provides_stresslets() const override {
    return plugin_call(who_, "provides_stresslets()", [&] { return in_->provides_stresslets(); });
  }
  Eigen::Matrix3d stresslet_sum(const System& s, const NodePairList& p, const double* dU) override {
    return plugin_call(who_, "stresslet_sum()",
                       [&] { return Eigen::Matrix3d(in_->stresslet_sum(s, p, dU)); });
  }
  std::vector<double> save_state() const override {
    return plugin_call(who_, "save_state()", [&] { return in_->save_state(); });
  }
  void restore_state(const std::vector<double>& state) override {
    plugin_call(who_, "restore_state()", [&] { in_->restore_state(state); });
  }

 private:
  std::shared_ptr<HydroModel> in_;
  std::string who_;
};

class GuardedForce : public ForceLaw, public GuardedNotes {
 public:
  GuardedForce(std::shared_ptr<ForceLaw> inner, std::string who)
      : GuardedNotes(run_notes_of(*inner), who), in_(std::move(inner)), who_(std::move(who)) {}
  double range(const System& s) const override {
    return plugin_call(who_, "range()", [&] { return in_->range(s); });
  }
  void add(const System& s, const NodePairList& p, double* wrench, Eigen::Matrix3d* virial) const override {
    plugin_call(who_, "add()", [&] { in_->add(s, p, wrench, virial); });
  }

 protected:
  std::shared_ptr<ForceLaw> in_;
  std::string who_;
};

// A force law that declares its pair energy (API 2.1) keeps declaring it through the guard, so
// pair_energy_of() finds it.
class GuardedEnergyForce final : public GuardedForce, public PairEnergy {
 public:
  GuardedEnergyForce(std::shared_ptr<ForceLaw> inner, const PairEnergy& energy, std::string who)
      : GuardedForce(std::move(inner), std::move(who)), energy_(energy) {}
  double pair_energy(const System& s, const NodePair& pair) const override {
    return plugin_call(who_, "pair_energy()", [&] { return energy_.pair_energy(s, pair); });
  }

 private:
  const PairEnergy& energy_;  // the inner object, kept alive by in_
};

class GuardedObserver final : public Observer, public GuardedNotes {
 public:
  GuardedObserver(std::shared_ptr<Observer> inner, std::string who)
      : GuardedNotes(run_notes_of(*inner), who), in_(std::move(inner)), who_(std::move(who)) {}
  ObserverNeeds needs() const override {
    return plugin_call(who_, "needs()", [&] { return in_->needs(); });
  }
  void begin(const System& s, const RunInfo& run, ResultSink& out) override {
    in_->set_schedule(every(), start());  // the core sets the schedule on this guard
    plugin_call(who_, "begin()", [&] { in_->begin(s, run, out); });
  }
  void sample(const StepView& view, ResultSink& out) override {
    plugin_call(who_, "sample()", [&] { in_->sample(view, out); });
  }
  void finish(const RunInfo& run, ResultSink& out) override {
    plugin_call(who_, "finish()", [&] { in_->finish(run, out); });
  }
  std::vector<double> save_state() const override {
    return plugin_call(who_, "save_state()", [&] { return in_->save_state(); });
  }
  void restore_state(const std::vector<double>& state) override {
    plugin_call(who_, "restore_state()", [&] { in_->restore_state(state); });
  }

 private:
  std::shared_ptr<Observer> in_;
  std::string who_;
};

// The guard for a plugin interface, or the object itself for any other interface (tests).
template <class T>
std::shared_ptr<T> guard_plugin_object(std::shared_ptr<T> inner, const std::string& who) {
  std::shared_ptr<T> out;
  if constexpr (std::is_same_v<T, Shape>)
    out = std::make_shared<GuardedShape>(std::move(inner), who);
  else if constexpr (std::is_same_v<T, HydroModel>)
    out = std::make_shared<GuardedHydro>(std::move(inner), who);
  else if constexpr (std::is_same_v<T, ForceLaw>) {
    if (const PairEnergy* energy = pair_energy_of(*inner))
      out = std::make_shared<GuardedEnergyForce>(inner, *energy, who);
    else
      out = std::make_shared<GuardedForce>(std::move(inner), who);
  } else if constexpr (std::is_same_v<T, Observer>)
    out = std::make_shared<GuardedObserver>(std::move(inner), who);
  else
    return inner;
  return out;
}

}  // namespace fldsim
