/* SPDX-License-Identifier: Apache-2.0 */
/* shadecore — the lighting core's host side in plain C99 (docs/driver.md): a GL-like lighting state (lights,
 * material, light model) → the register writes (address, data) of rtl/sc_light.v, the same words in the same
 * order as the C++ model's global_writes, material_writes, unit_material_writes, back_material_writes,
 * light_writes, light_off_writes, light_reset_writes and colour_material_writes (cmodel/include/shadecore/light.hpp;
 * tests/light_driver_test.cpp compares them on random states of every named feature set).
 *
 * The core a driver programs is described by an sc_light_config: its widths and the few capabilities the words
 * depend on (the feature set, or the RTL parameters it was built with: FRAC, SGUARD, LIGHTS, SLOT_KINDS/SLOT_SPOT,
 * UNITS, ENERGY, LOW_N). Writes are appended to a caller's buffer (sc_light_writes); a call that fails appends
 * nothing and returns a negative SC_LIGHT_ERR_*; no call writes outside the buffer. Addresses and formats come from
 * the generated shadecore/shadecore_light_regs.h (config/configs.json). No allocation, no globals, no I/O. */
#ifndef SHADECORE_LIGHT_DRIVER_H
#define SHADECORE_LIGHT_DRIVER_H

#include <stddef.h>
#include <stdint.h>

#include "shadecore/shadecore_light_regs.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Return values: 0 or a negative error (sc_light_strerror names it). */
enum {
  SC_LIGHT_OK = 0,
  SC_LIGHT_ERR_NULL = -1,        /* a NULL pointer */
  SC_LIGHT_ERR_CONFIG = -2,      /* the config describes no lighting core (widths, slots, units out of range) */
  SC_LIGHT_ERR_INDEX = -3,       /* a light index outside the core's slots */
  SC_LIGHT_ERR_RANGE = -4,       /* a value outside its range: colour [0, 2), attenuation [0, 256), position
                                    [-128, 128), shininess, spot cutoff (0..90 or 180), spot exponent 0..128,
                                    colour-material mode, coefficient kind */
  SC_LIGHT_ERR_KIND = -5,        /* the slot cannot take the kind, w contradicts the kind, a cutoff on a non-spot */
  SC_LIGHT_ERR_DIRECTION = -6,   /* a zero (or not finite) direction */
  SC_LIGHT_ERR_ATTENUATION = -7, /* kc = kl = kq = 0 (as codes) on an attenuated light */
  SC_LIGHT_ERR_UNIT = -8,        /* the material's unit is not in the core (or unknown), or its norm model is */
  SC_LIGHT_ERR_FEATURE = -9,     /* the state asks for a capability the core lacks (colour material) */
  SC_LIGHT_ERR_SPACE = -10       /* the buffer has no room for the writes (nothing appended) */
};
const char* sc_light_strerror(int err);

/* Kind of a light: one of SC_LIGHT_KIND_* or SC_LIGHT_KIND_AUTO (from w and the slot, as light_writes). */
#define SC_LIGHT_KIND_AUTO (-1)
/* colour material: SC_LIGHT_COLOUR_MATERIAL_* (0..4; 5..7 replace nothing) or SC_LIGHT_CM_NONE (off) */
#define SC_LIGHT_CM_NONE (-1)
/* the material's unit: a unit id SC_LIGHT_UNIT_* or SC_LIGHT_UNIT_DEFAULT (the core's first unit) */
#define SC_LIGHT_UNIT_DEFAULT (-1)
/* energy normalisation of the material (feature norm): a model index 0..5 (the paper's Table 1 order: phong,
 * phong_mod, blinn, blinn_mod, blinn_ndf, blinn_hf) or SC_LIGHT_NORM_OFF (coefficient 1.0) */
#define SC_LIGHT_NORM_OFF (-1)
#define SC_LIGHT_NUM_NORM_MODELS 6
#define SC_LIGHT_COEF_FITTED 0
#define SC_LIGHT_COEF_CLASSICAL 1

/* Writes per call, at most. */
#define SC_LIGHT_MAX_GLOBAL_WRITES 4
#define SC_LIGHT_MAX_UNIT_MATERIAL_WRITES 4
#define SC_LIGHT_MAX_MATERIAL_WRITES 16
#define SC_LIGHT_MAX_BACK_MATERIAL_WRITES 12
#define SC_LIGHT_MAX_LIGHT_WRITES 21
#define SC_LIGHT_MAX_STATE_WRITES \
  (SC_LIGHT_MAX_GLOBAL_WRITES + SC_LIGHT_MAX_MATERIAL_WRITES + SC_LIGHT_MAX_BACK_MATERIAL_WRITES + 1 + \
   SC_LIGHT_MAX_LIGHTS * SC_LIGHT_MAX_LIGHT_WRITES)

/* The core: LightCore's FeatureSet reduced to what the words depend on. */
typedef struct sc_light_config {
  int frac;            /* F: the config's frac (RTL FRAC), SC_LIGHT_FRAC_MIN..SC_LIGHT_FRAC_MAX */
  int unit_frac;       /* UF = F + spec_guard (FRAC + SGUARD): thr, coef and the spot cos are in this format */
  int num_lights;      /* light slots (LIGHTS), 1..SC_LIGHT_MAX_LIGHTS */
  uint32_t slot_kinds; /* bit 4j + k set: slot j can take kind k (SC_LIGHT_KIND_*) */
  uint32_t units;      /* bit v set: unit v (SC_LIGHT_UNIT_*) is in the core (UNITS); 0: no specular */
  int first_unit;      /* the unit a material selects by default: the feature set's first unit (cs16 without units) */
  uint32_t features;   /* SC_LIGHT_FEAT_*: NORM and LOW_SHININESS change words; LOCAL_VIEWER, BLINN, NORMALIZE the
                          default modes; COLOUR_MATERIAL lets a state write colour_material */
} sc_light_config;

/* The named feature set `name` of config/configs.json (SC_LIGHT_FS_LIST); SC_LIGHT_ERR_RANGE for another name. */
int sc_light_config_named(const char* name, sc_light_config* cfg);

/* glLight: one light (GL's defaults: sc_light_light_defaults). */
typedef struct sc_light_light {
  int kind;                  /* SC_LIGHT_KIND_AUTO or SC_LIGHT_KIND_* */
  int enabled;               /* GL_LIGHTi enabled (0 or not) */
  double position[4];        /* GL_POSITION in eye space; w = 0: directional (the direction to the light) */
  double ambient[3], diffuse[3], specular[3];  /* [0, 2) */
  double kc, kl, kq;         /* GL_CONSTANT/LINEAR/QUADRATIC_ATTENUATION, [0, 256) */
  double spot_direction[3];  /* GL_SPOT_DIRECTION in eye space, any non-zero length */
  double spot_cutoff;        /* degrees: 0..90, or 180 (no cone) */
  int spot_exponent;         /* 0..128 */
} sc_light_light;

/* glMaterial: one face's material (and the unit material of the front: unit, shininess, normalisation). */
typedef struct sc_light_material {
  double emission[3], ambient[3], diffuse[3], specular[3];  /* [0, 2) */
  int shininess;   /* 16..1024; 0..1024 with the feature low_shininess (or on a core without units) */
  int norm_model;  /* 0..5 or SC_LIGHT_NORM_OFF (feature norm only; ignored without it) */
  int norm_kind;   /* SC_LIGHT_COEF_FITTED or SC_LIGHT_COEF_CLASSICAL */
  int unit;        /* SC_LIGHT_UNIT_DEFAULT or SC_LIGHT_UNIT_* */
} sc_light_material;

/* glLightModel: the light_model register's modes. */
typedef struct sc_light_modes {
  int local_viewer, phong, normalize, separate_specular, two_side;  /* 0 or not */
} sc_light_modes;

/* A whole state, as sc_light_state_writes programs it. */
typedef struct sc_light_state {
  double global_ambient[3];
  sc_light_modes modes;
  sc_light_material material;       /* the front (and the unit material) */
  int has_back_material;            /* write the back colour bank from back_material */
  sc_light_material back_material;  /* colours only: both faces use the one unit material */
  int colour_material;              /* SC_LIGHT_CM_NONE or a mode; written when the core has colour material */
  int num_lights;                   /* lights[0 .. num_lights-1] are programmed, the core's other slots turned off */
  sc_light_light lights[SC_LIGHT_MAX_LIGHTS];
} sc_light_state;

/* GL's initial values (LightParams, MaterialParams, default_modes of light.hpp). */
void sc_light_light_defaults(sc_light_light* l);
void sc_light_material_defaults(sc_light_material* m);
int sc_light_default_modes(const sc_light_config* cfg, sc_light_modes* modes);
/* A state of GL's defaults for cfg: global ambient 0.2, default modes, default material, no back material,
 * colour material off, no lights. */
int sc_light_state_defaults(const sc_light_config* cfg, sc_light_state* st);

/* One register write. */
typedef struct sc_light_write {
  uint32_t addr, data;
} sc_light_write;
/* The caller's buffer: w[0 .. cap-1], count used. */
typedef struct sc_light_writes {
  sc_light_write* w;
  size_t cap, count;
} sc_light_writes;
void sc_light_writes_init(sc_light_writes* buf, sc_light_write* storage, size_t cap);

/* global_writes: light_model, then global_ambient r, g, b. */
int sc_light_global_writes(const sc_light_config* cfg, const double ambient[3], const sc_light_modes* modes,
                           sc_light_writes* out);
/* unit_material_writes: mat_unit, mat_n, mat_thr, mat_coef. */
int sc_light_unit_material_writes(const sc_light_config* cfg, const sc_light_material* m, sc_light_writes* out);
/* material_writes: the unit material, then per channel emission, ambient, diffuse, specular. */
int sc_light_material_writes(const sc_light_config* cfg, const sc_light_material* m, sc_light_writes* out);
/* back_material_writes: per channel the back bank's emission, ambient, diffuse, specular. */
int sc_light_back_material_writes(const sc_light_config* cfg, const sc_light_material* back, sc_light_writes* out);
/* light_writes: light j's mode, position, colours, attenuation (point_att, spot), spot registers (spot). */
int sc_light_light_writes(const sc_light_config* cfg, int j, const sc_light_light* l, sc_light_writes* out);
/* light_off_writes: light j's mode word 0. */
int sc_light_light_off_writes(const sc_light_config* cfg, int j, sc_light_writes* out);
/* light_reset_writes: GL's initial state of slot j, light off (a driver's context creation). */
int sc_light_light_reset_writes(const sc_light_config* cfg, int j, sc_light_writes* out);
/* colour_material_writes: mode SC_LIGHT_CM_NONE (off) or 0..7. */
int sc_light_colour_material_writes(int mode, sc_light_writes* out);
/* The whole state: global, material, back material (if given), colour material (if the core has it), then for
 * every slot j light_writes (j < num_lights) or light_off_writes. All or nothing. */
int sc_light_state_writes(const sc_light_config* cfg, const sc_light_state* st, sc_light_writes* out);

/* The energy-normalisation coefficient (a·n + b)/(k·π) (fitted) or the classical one of a model, in double, as
 * units/coef.hpp's coef_value: what mat_coef rounds. NaN for a bad model or kind. */
double sc_light_energy_coef(int model, int kind, double n);

#ifdef __cplusplus
}
#endif

#endif /* SHADECORE_LIGHT_DRIVER_H */
