"""Implicit dynamics (generalized-alpha) on an elastic bar clamped at one end,
set in motion by an initial velocity, small amplitude (linear regime):

 - rho_inf = 1 (the trapezoidal / mid-point member) conserves the total
   energy: kinetic 1/2 v'Mv plus the elastic energy computed from the stresses
   (1/2 sigma : H^-1 : sigma, a state function independent of the work
   bookkeeping) changes by less than 1e-6 of the initial energy per step, for
   the smoothest mode (sin(pi x / 2L)) and the roughest one the mesh carries
   (cos(pi x / h)); the work balance W_ext + K0 - K - W_sigma (nodes against
   the points' stress work, doc/energy_audit.md) closes to 1e-8: at rho_inf =
   1 the free dofs are in balance on the average of t_n and t_n+1, which is
   the trapezoid of the work, so only the Newton tolerance and the third-order
   geometric terms (~1e-9 here) remain;
 - rho_inf = 0.5 damps only the high frequencies: after 10 steps of T1/50 the
   smooth mode keeps > 99 % of its energy while the rough one keeps < 5 %."""
from anvil_test import run, read_csv, check, finish

modes = {"smooth": "ux = 1*sin(pi*x/200)", "rough": "ux = 1*cos(pi*x/2)"}
for rho in (1, 0.5):
    for name, v0 in modes.items():
        out, s, _ = run("tests/dynamics_bar.prm", ["Mechanics/Dynamics/Initial velocity=" + v0,
                                                   "Mechanics/Dynamics/Spectral radius=%g" % rho,
                                                   "Time/End time=1.6e-5"],
                        name="dynamics_%s_rho%g" % (name, rho))
        e = read_csv(out + "/energy.csv")
        E = [k + u for k, u in zip(e["kinetic_energy"], e["elastic_energy"])]
        step_change = max(abs(E[i + 1] - E[i]) / E[0] for i in range(len(E) - 1))
        print("  rho_inf = %g, %s mode: E_end / E0 = %.6f, largest change per step %.2e of E0, work balance %.2e, "
              "%d steps, %d Newton iterations"
              % (rho, name, E[-1] / E[0], step_change, max(e["balance_error"]), s["steps"], s["newton_iterations"]))
        if rho == 1:
            check(step_change < 1e-6, "rho_inf = 1, %s mode: energy conserved to %.2e per step" % (name, step_change))
            check(max(e["balance_error"]) < 1e-8, "rho_inf = 1, %s mode: W_ext + K0 - K - W_sigma = %.2e" % (name, max(e["balance_error"])))
        elif name == "smooth":
            check(E[-1] / E[0] > 0.99, "rho_inf = 0.5 keeps the smooth mode (%.4f of its energy)" % (E[-1] / E[0]))
        else:
            check(E[-1] / E[0] < 0.05, "rho_inf = 0.5 damps the mesh mode (%.4f of its energy left)" % (E[-1] / E[0]))
finish()
