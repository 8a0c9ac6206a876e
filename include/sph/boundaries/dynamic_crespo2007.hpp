// Dynamic boundary particles (Crespo, Gomez-Gesteira & Dalrymple 2007,
// Comput. Mater. Contin. 5; the boundary of DualSPHysics, Crespo et al.
// 2015, Comput. Phys. Commun. 187): wall particles that do not move but
// carry a density by the continuity equation from their fluid neighbours,
//
//   d rho_w / dt = sum_f m_f (v_w - v_f) . grad_w W_wf,
//
// and a pressure by the same equation of state as the fluid. A fluid
// particle that comes close compresses them, their pressure rises and the
// fluid's own pressure term pushes it back. They enter the fluid's
// pressure, viscosity and continuity terms like fluid particles, with their
// own (prescribed) velocity; no density diffusion, no XSPH.
//
// In the pass list (models/wcsph.hpp) this is: the EOS pass over walls too,
// and the wall-particle density rates of the force pass; the integrator then
// advances the walls' density with the fluid's. Known behaviour: the fluid
// stands off the wall by about one smoothing length, and the first fluid
// layer's pressure is a little noisy (Crespo et al. 2007).
#pragma once
