// A brake's or clutch's lumped temperature, an output of a run (docs/friction-elements.md,
// "Temperature"): heated by the element's slip power, cooled through a conductance to a fixed
// ambient temperature. It does not act on the friction.
#pragma once

#include <cmath>

namespace pogear::rt {

// C dT/dt = P - G (T - T_a): element `element` (an index into the run's brakes and clutches), its
// heat capacity C [J/K], conductance G [W/K] (0: adiabatic), ambient and initial temperatures [degC].
struct ElementThermal {
  int element = -1;
  double heat_capacity = 0, conductance = 0, ambient = 0, initial = 0;
};

// The temperature a sample period h after T, the element having dissipated dE [J] over it: the exact
// solution for a slip power constant over h (dE / h), and for any power when G = 0. Otherwise the
// power's variation within h weighs the heat by at most (h / tau) of its own, tau = C / G: the
// temperature rise is exact to a relative h / (2 tau) (1e-6 for 1 ms against 500 s).
inline double next_temperature(const ElementThermal& e, double T, double dE, double h) {
  if (e.conductance == 0) return T + dE / e.heat_capacity;
  const double a = h * e.conductance / e.heat_capacity;  // h / tau
  // (1 - e^-a) / a by expm1: no cancellation when h is far below tau.
  return e.ambient + (T - e.ambient) * std::exp(-a) + dE / e.heat_capacity * (-std::expm1(-a) / a);
}

}  // namespace pogear::rt
