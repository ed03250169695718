/* config.h: the resolved run configuration, plain data.
 *
 * io/ parses an input file into this struct (with defaults, ranges and
 * overrides); scenario/ and solver/ build a simulation from it. Numerical code
 * never parses text: this struct is the only channel from input to solver.
 * Every field is documented with its unit in docs/input-reference.md. */
#ifndef MPM_CORE_CONFIG_H
#define MPM_CORE_CONFIG_H

#define MPM_NAME_MAX 32
#define MPM_PATH_MAX 1024
#define MPM_MAX_FILLS 16
#define MPM_MAX_POLY 64
#define MPM_MAX_BODIES 8

/* Boundary condition on one mesh edge (velocity part). */
enum mpm_bc_kind {
  MPM_BC_FREE = 0,      /* nothing constrained */
  MPM_BC_NOSLIP,        /* rough wall: both velocity components zero */
  MPM_BC_FRICTIONLESS,  /* normal component zero */
  MPM_BC_SYMMETRY,      /* normal component zero (mirror plane) */
  MPM_BC_PERIODIC       /* opposite edge aliased; must be set on both */
};

/* Mesh edge carrying an outlet. */
enum mpm_outlet_edge {
  MPM_OUTLET_NONE = 0, MPM_OUTLET_LEFT, MPM_OUTLET_RIGHT, MPM_OUTLET_BOTTOM, MPM_OUTLET_TOP,
  MPM_OUTLET_FRONT, MPM_OUTLET_BACK    /* 3D: the z faces */
};

/* The shape of a 3D outlet on its face. */
enum mpm_outlet_shape { MPM_OUTLET_RECTANGLE = 0, MPM_OUTLET_DISC };

/* The nodes at the ends of a plane outlet [from, to]: free (the orifice is
 * the distance between its first and last free node, [DK15] section 4.2) or
 * held (the distance between the held nodes that bound it, [DK-silo]
 * section 7.1: "measured from fixed-node to fixed-node"). */
enum mpm_outlet_ends { MPM_OUTLET_ENDS_FREE = 0, MPM_OUTLET_ENDS_FIXED };

enum mpm_fill_shape { MPM_FILL_RECTANGLE = 0, MPM_FILL_DISC, MPM_FILL_POLYGON };

/* Where the volumetric part of the scheme lives: at the point (standard
 * MPM), per unit (B-bar with one mean stress per unit) or per unit with the
 * filled units integrated as mixed Q1/P0 elements (docs/model.md). */
enum mpm_dilatation { MPM_DILATATION_POINT = 0, MPM_DILATATION_UNIT, MPM_DILATATION_ELEMENT };

/* How the point velocities are transferred: FLIP blended with PIC by
 * time.flip, or affine (APIC: the PIC velocity and the affine matrix
 * C_p = sum_i v_i (x) gradS_ip). */
enum mpm_transfer { MPM_TRANSFER_FLIP = 0, MPM_TRANSFER_APIC };

typedef struct mpm_fill_config {
  int shape;                   /* enum mpm_fill_shape */
  double xmin, ymin, xmax, ymax;  /* rectangle [m] */
  double cx, cy, radius;       /* disc [m] */
  int nvert;                   /* polygon vertices (counter-clockwise or not) */
  double px[MPM_MAX_POLY], py[MPM_MAX_POLY];
  int ppu;                     /* points per unit along each direction (n x n) */
  double density;              /* initial density [kg/m^3] */
  double vx, vy;               /* initial velocity [m/s] */
  double zmin, zmax;           /* 3D (mesh.nz > 0): the z range of the fill, which
                                  extrudes its plane shape along z [m] */
  double vz;                   /* 3D: initial velocity z [m/s] */
  int axis;                    /* 3D disc: the cylinder's axis, 0 x, 1 y, 2 z (the
                                  input's default; a configuration made in code
                                  sets it: 0 is x); along x its circle has the
                                  centre (cy, cz) and it spans xmin ... xmax,
                                  along y (cx, cz) and ymin ... ymax */
  double cz;                   /* 3D disc along x or y: the centre's z [m] */
  int lithostatic;             /* 1: pre-stress from the weight above */
  double k0;                   /* lithostatic: sigma_xx = sigma_zz = k0 sigma_yy (0: the
                                  uniaxial-strain value nu/(1-nu)) */
  double pressure;             /* isotropic initial pressure [Pa] (0: none) */
  char name[MPM_NAME_MAX];     /* title of the fill section ("fill NAME { ... }") */
} mpm_fill_config;

/* A rigid body (docs/input-reference.md, section body): a plane profile (a
 * disc, a rectangle or a polygon) in the plane normal to its axis, turned by
 * its angle about the axis through its centre and, in 3D, extruded along the
 * axis; the material lies outside it (a blade, a wheel, an inner cylinder)
 * or inside it (an outer cylinder's wall). */
enum mpm_body_shape { MPM_BODY_DISC = 0, MPM_BODY_BOX, MPM_BODY_POLYGON };
enum mpm_body_side { MPM_BODY_OUTSIDE = 0, MPM_BODY_INSIDE };
enum mpm_body_contact { MPM_CONTACT_NOSLIP = 0, MPM_CONTACT_FRICTIONLESS, MPM_CONTACT_FRICTION };

/* The velocity degrees of freedom of a body: x, y, z, and the rotation about
 * its axis. */
enum { MPM_BODY_VX = 0, MPM_BODY_VY, MPM_BODY_VZ, MPM_BODY_OMEGA, MPM_BODY_NDOF };

typedef struct mpm_body_config {
  int shape;                   /* enum mpm_body_shape */
  int axis;                    /* 3D: the axis 0 x, 1 y, 2 z (plane: z); a polygon's
                                  only along z */
  double cx, cy, cz;           /* centre: the reference point of the profile and of
                                  the rotation [m] */
  double radius;               /* disc [m] */
  double hx, hy;               /* box: half-sizes of the rectangle along the profile's
                                  axes before the turn (axis z: x, y; x: y, z;
                                  y: z, x) [m] */
  int nvert;                   /* polygon: vertices relative to the centre [m] */
  double px[MPM_MAX_POLY], py[MPM_MAX_POLY];
  double angle;                /* initial turn about the axis [deg] */
  double length;               /* 3D: extent along the axis, centred [m]; 0: through
                                  the mesh */
  int side;                    /* enum mpm_body_side: where the material is */
  int contact;                 /* enum mpm_body_contact */
  double friction;             /* Coulomb coefficient of MPM_CONTACT_FRICTION */
  /* Motion of each degree of freedom (MPM_BODY_VX ... MPM_BODY_OMEGA):
   * prescribed, its velocity [m/s] or angular velocity [rad/s] linear in time
   * between the entries of the table t (one value: constant), or free. */
  int ntable;                  /* entries of t (0: every value constant) */
  double t[MPM_MAX_POLY];      /* increasing times [s] */
  int nval[MPM_BODY_NDOF];     /* values given: 1 or ntable */
  double val[MPM_BODY_NDOF][MPM_MAX_POLY];
  int free[MPM_BODY_NDOF];     /* 1: integrated from the forces */
  double mass;                 /* of a free body [kg; plane kg/m] */
  double inertia;              /* about its axis [kg m^2; plane kg m^2/m] */
  double force[3];             /* applied force [N; plane N/m] */
  double torque;               /* applied torque about the axis [N m; plane N m/m] */
  double damping;              /* linear damping rate of a free motion [1/s] */
  int carve;                   /* 1: the fill's points inside the body are not made */
  char name[MPM_NAME_MAX];     /* title of the section ("body NAME { ... }") */
} mpm_body_config;

typedef struct mpm_config {
  char source[MPM_PATH_MAX];   /* input file the values came from */

  struct {
    int nx, ny;                /* units along x and y */
    double x0, y0;             /* lower-left corner [m] */
    double dx, dy;             /* unit size [m] */
    int nz;                    /* units along z: 0 a plane-strain run, > 0 a 3D one
                                  (boxes of dx x dy x dz; y stays the vertical) */
    double z0, dz;             /* 3D: the z of the mesh's origin, the unit depth [m] */
    char topology[MPM_NAME_MAX];  /* "q4" | "t3" */
    char diagonal[MPM_NAME_MAX];  /* "/" "\\" "mirror" (T3 only) */
    double mirror_x;           /* x of the mirror line [m] */
    char shape[MPM_NAME_MAX];  /* shape-function variant: "delta" | "ugimp" */
    int dilatation;            /* enum mpm_dilatation ("point" | "unit" | "element") */
  } mesh;

  struct {
    double dt;                 /* time step [s]; 0: from cfl */
    double cfl;                /* dt = cfl * min(dx,dy) / c_p when dt = 0 */
    double t_end;              /* end time [s] */
    double frame_dt;           /* output interval [s] */
    double flip;               /* FLIP share of the point velocity update (1: pure
                                  FLIP, [DK15]; 0: PIC) */
    int dt_unstable_ok;        /* 1: a dt above the stable step is deliberate */
    int transfer;              /* enum mpm_transfer ("flip" | "apic") */
  } time;

  struct {
    double gx, gy;             /* final gravity vector [m/s^2] (from angle and g when
                                  use_angle) */
    double gz;                 /* 3D: its z component [m/s^2] */
    double angle;              /* incline angle [deg]: gx = g sin, gy = -g cos */
    double g;                  /* magnitude for angle [m/s^2] */
    int use_angle;             /* 1: gravity was given as angle and g */
    double t_ramp;             /* linear ramp from 0 over t_ramp [s]; 0 = none */
  } gravity;

  struct {
    char model[MPM_NAME_MAX];  /* material table name: "elastic", "mu_i", ... */
    double E, nu;              /* Young's modulus [Pa], Poisson ratio */
    double rho_s, rho_c;       /* grain and critical density [kg/m^3] */
    double mu_s, mu_2, I0, d;  /* mu(I) parameters; d grain diameter [m] */
    double A, t0;              /* NGF nonlocal amplitude, time scale [s] */
    int form;                  /* NGF PDE form, enum mpm_material_ngf_form ("dk" | "hs21") */
    int p_sample;              /* NGF g^2 term's p^-1/2, enum mpm_material_ngf_p_sample
                                  ("point" | "unit") */
    int g_average;             /* NGF point shares in the unit averages, enum
                                  mpm_nonlocal_rule ("centre" | "extent") */
    double t_seed;             /* NGF: local mu(I) update while t < t_seed [s] */
    int diffusion;             /* NGF fluidity solver, enum mpm_nonlocal_diffusion_kind
                                  ("explicit" | "implicit" | "steady") */
    int g_wall;                /* NGF g on no-slip walls, enum mpm_nonlocal_wall
                                  ("dirichlet": g = 0 | "neumann": zero flux) */
    int g_sample;              /* steady solve: how points read g, enum
                                  mpm_nonlocal_steady_sample ("element" | "linear") */
    int g_mass;                /* steady solve: the w S S term, enum
                                  mpm_nonlocal_steady_mass ("consistent" | "lumped") */
    int n_sub;                 /* constitutive substeps per MPM step (L fixed) */
    double dt_sub;             /* target substep [s]: n_sub = ceil(dt / dt_sub); 0: use n_sub */
    int state_density;         /* density of the state decision, enum mpm_material_density_rule
                                  ("point" | "element" | "hybrid", [D-thesis] §3.4) */
  } material;

  struct {
    int left, right, bottom, top;  /* enum mpm_bc_kind */
    int front, back;               /* 3D: the faces z = z0 and z = z0 + nz dz */
    int wall_acceleration;         /* enum mpm_bc_wall_acceleration: what the points
                                      get from a held velocity component */
  } bc;

  int nfill;
  mpm_fill_config fill[MPM_MAX_FILLS];

  int nbody;
  mpm_body_config body[MPM_MAX_BODIES];

  struct {
    double ke;                 /* end the run when kinetic energy per unit mass
                                  falls below this [J/kg]; 0: never */
    double t_min;              /* ... but not before this time [s] */
    double mass;               /* end the run when the mass in region falls below
                                  this [kg/m]; 0: never */
  } stop;

  struct {
    char dir[MPM_PATH_MAX];    /* run directory */
    double checkpoint_dt;      /* checkpoint every this much simulated time [s]; 0: off */
    double checkpoint_wall;    /* checkpoint every this much wall-clock time [s]; 0: off */
    int allow_large;           /* 1: run even when the size estimate exceeds the
                                  machine's memory or the output's free space */
  } output;

  /* Silo and hourglass features (docs/input-reference.md). */
  struct {
    int edge;                  /* enum mpm_outlet_edge; MPM_OUTLET_NONE: no outlet */
    double from, to;           /* extent along the edge (x on bottom/top, y on
                                  left/right) [m]; 3D: along the face's first axis
                                  (x on bottom/top/front/back, y on left/right) */
    double from2, to2;         /* 3D: extent along the face's second axis (z on
                                  left/right/bottom/top, y on front/back) [m] */
    int shape;                 /* 3D: enum mpm_outlet_shape; a disc is the one
                                  inscribed in the square [from, to] x [from2, to2] */
    double t_open;             /* closed before, open from this time on [s] */
    int closed;                /* enum mpm_bc_kind while closed (noslip, frictionless) */
    int ends;                  /* plane: enum mpm_outlet_ends ("free" | "fixed") */
  } outlet;

  struct {
    int nvert;                 /* 0: no wall */
    double px[MPM_MAX_POLY], py[MPM_MAX_POLY];  /* polygon [m] */
    int kind;                  /* enum mpm_bc_kind: noslip or frictionless */
  } wall;

  struct {
    double below;              /* remove points whose y falls below this [m] */
    int free_edges;            /* 1: points leaving through a free edge are removed */
  } remove;

  struct {
    double xmin, xmax, ymin, ymax;  /* region whose mass is reported [m] */
    double m_hi, m_lo;         /* flow-rate fit between these masses [kg/m]; 0: none */
  } region;

  struct {
    double above;              /* elastic-wave absorbing layer: points at or above
                                  this y [m] ... */
    double factor;             /* ... have an upward velocity multiplied by this */
  } absorb;
} mpm_config;

#endif
