/* state.h: `granmpm state`: the state plot of [DK15] Fig. 7. */
#ifndef MPM_APP_STATE_H
#define MPM_APP_STATE_H

/* granmpm state INPUT RUNDIR [--frame N|last]: one frame's points with the
 * nodal density projected back to them and the state it gives, as CSV
 * (x,y,rho_nodal,state_nodal; state 1: rho_nodal < rho_c, disconnected).
 * Returns the exit status. */
int mpm_app_state(int argc, char **argv);

#endif
