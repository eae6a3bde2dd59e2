/* SPDX-License-Identifier: Apache-2.0 */
/* shadecore — the lighting core's host side in C99 (shadecore_light_driver.h, docs/driver.md).
 *
 * Every conversion below is the C++ model's (cmodel/include/shadecore/light.hpp, unit.hpp, units/cs16.hpp,
 * units/coef.hpp) statement for statement, in the same IEEE double operations and libm calls, so that the words are
 * bit-identical (tests/light_driver_test.cpp): a colour is min(llround(ldexp(x, F)), 2^(F+1) − 1), a threshold
 * ceil(ldexp(cos(6/sqrt(n)), UF)), and so on. Where the C++ throws, the C returns an error and appends nothing. */
#include "shadecore_light_driver.h"

#include <math.h>
#include <string.h>

/* M_PI is POSIX, not C99: the same double (units/coef.hpp uses M_PI) */
#define SC_PI 3.14159265358979323846

/* ---- buffer ------------------------------------------------------------------------------------------------- */
/* Writes of one call collect in a local list (at most SC_LIGHT_MAX_STATE_WRITES) and are copied to the caller's
 * buffer only when the call succeeds and they fit. */
typedef struct {
  sc_light_write w[SC_LIGHT_MAX_STATE_WRITES];
  size_t n;
} wlist;

static void push(wlist* l, uint32_t addr, uint32_t data) {
  if (l->n < sizeof l->w / sizeof l->w[0]) {
    l->w[l->n].addr = addr;
    l->w[l->n].data = data;
    ++l->n;
  }
}

static int commit(const wlist* l, sc_light_writes* out) {
  if (out->count > out->cap || out->cap - out->count < l->n) return SC_LIGHT_ERR_SPACE;
  if (l->n) memcpy(out->w + out->count, l->w, l->n * sizeof l->w[0]);
  out->count += l->n;
  return SC_LIGHT_OK;
}

static int check_out(const sc_light_writes* out) {
  if (!out || (!out->w && out->cap)) return SC_LIGHT_ERR_NULL;
  return SC_LIGHT_OK;
}

void sc_light_writes_init(sc_light_writes* buf, sc_light_write* storage, size_t cap) {
  if (!buf) return;
  buf->w = storage;
  buf->cap = storage ? cap : 0;
  buf->count = 0;
}

const char* sc_light_strerror(int err) {
  switch (err) {
    case SC_LIGHT_OK: return "ok";
    case SC_LIGHT_ERR_NULL: return "NULL pointer";
    case SC_LIGHT_ERR_CONFIG: return "the config describes no lighting core";
    case SC_LIGHT_ERR_INDEX: return "light index outside the core's slots";
    case SC_LIGHT_ERR_RANGE: return "value out of range";
    case SC_LIGHT_ERR_KIND: return "light kind not possible (slot kinds, w, spot cutoff)";
    case SC_LIGHT_ERR_DIRECTION: return "zero direction";
    case SC_LIGHT_ERR_ATTENUATION: return "constant, linear and quadratic attenuation all 0";
    case SC_LIGHT_ERR_UNIT: return "specular unit or normalisation model not in this core";
    case SC_LIGHT_ERR_FEATURE: return "capability not in this core";
    case SC_LIGHT_ERR_SPACE: return "no room in the write buffer";
    default: return "unknown error";
  }
}

/* ---- config ------------------------------------------------------------------------------------------------- */
static int unit_known(int v) { return v >= 0 && v < 32 && ((SC_LIGHT_UNITS_KNOWN >> v) & 1u); }

static int check_config(const sc_light_config* c) {
  if (!c) return SC_LIGHT_ERR_NULL;
  if (c->frac < SC_LIGHT_FRAC_MIN || c->frac > SC_LIGHT_FRAC_MAX) return SC_LIGHT_ERR_CONFIG;
  if (c->unit_frac < c->frac + SC_LIGHT_SPEC_GUARD_MIN || c->unit_frac > c->frac + SC_LIGHT_SPEC_GUARD_MAX ||
      c->unit_frac > SC_LIGHT_UNIT_FRAC_MAX)
    return SC_LIGHT_ERR_CONFIG;
  if (c->num_lights < 1 || c->num_lights > SC_LIGHT_MAX_LIGHTS) return SC_LIGHT_ERR_CONFIG;
  if ((c->units & ~(uint32_t)SC_LIGHT_UNITS_KNOWN) != 0 || !unit_known(c->first_unit)) return SC_LIGHT_ERR_CONFIG;
  if (c->units && !((c->units >> c->first_unit) & 1u)) return SC_LIGHT_ERR_CONFIG;
  return SC_LIGHT_OK;
}

static int slot_can(const sc_light_config* c, int j, int kind) {
  return kind >= 0 && kind < SC_LIGHT_NUM_KINDS && ((c->slot_kinds >> (4 * j + kind)) & 1u);
}
/* FeatureSet::slot_kind: the first kind slot j can take (directional for none) */
static int slot_kind(const sc_light_config* c, int j) {
  int k;
  for (k = 0; k < SC_LIGHT_NUM_KINDS; ++k)
    if (slot_can(c, j, k)) return k;
  return SC_LIGHT_KIND_DIRECTIONAL;
}
static int has_att(int kind) { return kind == SC_LIGHT_KIND_POINT_ATT || kind == SC_LIGHT_KIND_SPOT; }

int sc_light_config_named(const char* name, sc_light_config* cfg) {
  if (!name || !cfg) return SC_LIGHT_ERR_NULL;
#define SC_LIGHT_NAMED_(lower, UPPER)                      \
  if (strcmp(name, #lower) == 0) {                         \
    cfg->frac = SC_LIGHT_FS_##UPPER##_FRAC;                \
    cfg->unit_frac = SC_LIGHT_FS_##UPPER##_UNIT_FRAC;      \
    cfg->num_lights = SC_LIGHT_FS_##UPPER##_LIGHTS;        \
    cfg->slot_kinds = SC_LIGHT_FS_##UPPER##_SLOT_KINDS;    \
    cfg->units = SC_LIGHT_FS_##UPPER##_UNITS;              \
    cfg->first_unit = SC_LIGHT_FS_##UPPER##_FIRST_UNIT;    \
    cfg->features = SC_LIGHT_FS_##UPPER##_FEATURES;        \
    return SC_LIGHT_OK;                                    \
  }
  SC_LIGHT_FS_LIST(SC_LIGHT_NAMED_)
#undef SC_LIGHT_NAMED_
  return SC_LIGHT_ERR_RANGE;
}

/* ---- defaults ----------------------------------------------------------------------------------------------- */
void sc_light_light_defaults(sc_light_light* l) {
  int c;
  if (!l) return;
  memset(l, 0, sizeof *l);
  l->kind = SC_LIGHT_KIND_AUTO;
  l->enabled = 1;
  l->position[2] = 1.0;  /* (0, 0, 1, 0) */
  for (c = 0; c < 3; ++c) l->diffuse[c] = l->specular[c] = 1.0;
  l->kc = 1.0;
  l->spot_direction[2] = -1.0;
  l->spot_cutoff = 180.0;
}

void sc_light_material_defaults(sc_light_material* m) {
  int c;
  if (!m) return;
  memset(m, 0, sizeof *m);
  for (c = 0; c < 3; ++c) {
    m->ambient[c] = 0.2;
    m->diffuse[c] = 0.8;
  }
  m->shininess = 64;
  m->norm_model = 0;
  m->norm_kind = SC_LIGHT_COEF_FITTED;
  m->unit = SC_LIGHT_UNIT_DEFAULT;
}

int sc_light_default_modes(const sc_light_config* cfg, sc_light_modes* md) {
  const int e = check_config(cfg);
  if (e) return e;
  if (!md) return SC_LIGHT_ERR_NULL;
  md->local_viewer = (cfg->features & SC_LIGHT_FEAT_LOCAL_VIEWER) != 0;
  md->phong = (cfg->features & SC_LIGHT_FEAT_BLINN) == 0;
  md->normalize = (cfg->features & SC_LIGHT_FEAT_NORMALIZE) != 0;
  md->separate_specular = 0;
  md->two_side = 0;
  return SC_LIGHT_OK;
}

int sc_light_state_defaults(const sc_light_config* cfg, sc_light_state* st) {
  int e, c, j;
  if (!st) return SC_LIGHT_ERR_NULL;
  memset(st, 0, sizeof *st);
  e = sc_light_default_modes(cfg, &st->modes);
  if (e) return e;
  for (c = 0; c < 3; ++c) st->global_ambient[c] = 0.2;
  sc_light_material_defaults(&st->material);
  sc_light_material_defaults(&st->back_material);
  st->colour_material = SC_LIGHT_CM_NONE;
  for (j = 0; j < SC_LIGHT_MAX_LIGHTS; ++j) sc_light_light_defaults(&st->lights[j]);
  return SC_LIGHT_OK;
}

/* ---- codes (light.hpp detail::) ----------------------------------------------------------------------------- */
/* colour_code: [0, 2) → min(llround(x·2^F), 2^(F+1) − 1) */
static int colour_code(int F, double x, uint32_t* code) {
  long long v, hi;
  if (!(x >= 0.0) || x >= 2.0) return SC_LIGHT_ERR_RANGE;
  v = llround(ldexp(x, F));
  hi = (1LL << (F + 1)) - 1;
  *code = (uint32_t)(hi < v ? hi : v);
  return SC_LIGHT_OK;
}
/* attc_code: [0, 256) → min(llround(x·2^F), 2^(F+8) − 1) */
static int attc_code(int F, double x, uint32_t* code) {
  long long v, hi;
  if (!(x >= 0.0) || x >= 256.0) return SC_LIGHT_ERR_RANGE;
  v = llround(ldexp(x, F));
  hi = (1LL << (F + SC_LIGHT_FMT_ATT_COEF_INT_BITS)) - 1;
  *code = (uint32_t)(hi < v ? hi : v);
  return SC_LIGHT_OK;
}
/* pos_code: [−128, 128) → clamp(llround(x·2^F), −2^(F+7), 2^(F+7) − 1) */
static int pos_code(int F, double x, int64_t* code) {
  int64_t v, lo, hi;
  if (!(x >= -128.0) || !(x < 128.0)) return SC_LIGHT_ERR_RANGE;
  v = (int64_t)llround(ldexp(x, F));
  lo = -((int64_t)1 << (F + SC_LIGHT_FMT_POSITION_INT_BITS));
  hi = ((int64_t)1 << (F + SC_LIGHT_FMT_POSITION_INT_BITS)) - 1;
  *code = v < lo ? lo : (hi < v ? hi : v);
  return SC_LIGHT_OK;
}
/* push_unit_direction: d / |d| (double), each component llround(·2^F), masked */
static int push_unit_direction(wlist* w, uint32_t addr, int F, const double d[3], uint32_t mask) {
  uint32_t c;
  const double l = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  if (!(l > 0)) return SC_LIGHT_ERR_DIRECTION;
  for (c = 0; c < 3; ++c) push(w, addr + c, (uint32_t)llround(ldexp(d[c] / l, F)) & mask);
  return SC_LIGHT_OK;
}

/* ---- energy coefficient (units/coef.hpp) -------------------------------------------------------------------- */
/* kModels: (a, b, k) of the paper's fitted coefficient (a·n + b)/(k·π), in its Table 1 order */
static const struct {
  double a, b;
  int k;
} kModels[SC_LIGHT_NUM_NORM_MODELS] = {
    {1.063, 0.0, 2}, {1.063, 1.0, 2}, {1.068, 0.96, 8}, {1.027, 4.8, 8}, {1.063, 0.0, 2}, {1.063, 1.0, 2},
};

static double classical_coef(int m, double n) {
  const double pi = SC_PI;
  switch (m) {
    case 0: /* Phong */
    case 4: /* BlinnNdf */ return (n + 1) / (2 * pi);
    case 1: /* PhongMod */
    case 5: /* BlinnHeightfield */ return (n + 2) / (2 * pi);
    case 2: /* Blinn */ return (n + 2) / (4 * pi * (2 - exp2(-n / 2)));
    case 3: /* BlinnMod */ return (n + 2) * (n + 4) / (8 * pi * (exp2(-n / 2) + n));
    default: return (double)NAN;
  }
}

double sc_light_energy_coef(int model, int kind, double n) {
  if (model < 0 || model >= SC_LIGHT_NUM_NORM_MODELS) return (double)NAN;
  if (kind == SC_LIGHT_COEF_FITTED) return (kModels[model].a * n + kModels[model].b) / (kModels[model].k * SC_PI);
  if (kind == SC_LIGHT_COEF_CLASSICAL) return classical_coef(model, n);
  return (double)NAN;
}

/* coef_code: floor(coef·2^UF + 1/2), fits kCoefIntBits + UF bits */
static int coef_code(int uf, double coef, uint32_t* code) {
  double scaled;
  if (!isfinite(coef) || coef < 0) return SC_LIGHT_ERR_RANGE;
  scaled = floor(ldexp(coef, uf) + 0.5);
  if (scaled >= ldexp(1.0, uf + SC_LIGHT_FMT_COEF_INT_BITS)) return SC_LIGHT_ERR_RANGE;
  *code = (uint32_t)scaled;
  return SC_LIGHT_OK;
}

/* ---- writes ------------------------------------------------------------------------------------------------- */
static int global_list(const sc_light_config* cfg, const double ambient[3], const sc_light_modes* md, wlist* w) {
  uint32_t c, word, code;
  int e;
  word = (md->local_viewer ? SC_LIGHT_LM_LOCAL_VIEWER : 0u) | (md->phong ? SC_LIGHT_LM_PHONG : 0u) |
         (md->normalize ? SC_LIGHT_LM_NORMALIZE : 0u) | (md->separate_specular ? SC_LIGHT_LM_SEPARATE_SPECULAR : 0u) |
         (md->two_side ? SC_LIGHT_LM_TWO_SIDE : 0u);
  push(w, SC_LIGHT_REG_LIGHT_MODEL, word);
  for (c = 0; c < 3; ++c) {
    if ((e = colour_code(cfg->frac, ambient[c], &code))) return e;
    push(w, SC_LIGHT_REG_GLOBAL_AMBIENT + c, code);
  }
  return SC_LIGHT_OK;
}

int sc_light_global_writes(const sc_light_config* cfg, const double ambient[3], const sc_light_modes* modes,
                           sc_light_writes* out) {
  wlist w;
  int e;
  if ((e = check_config(cfg)) || (e = check_out(out))) return e;
  if (!ambient || !modes) return SC_LIGHT_ERR_NULL;
  w.n = 0;
  if ((e = global_list(cfg, ambient, modes, &w))) return e;
  return commit(&w, out);
}

/* unit_material_writes (light.hpp) with Unit::setup (unit.hpp): cs16 and its forms cs16_setup's threshold, the
 * Schlick and table units none; energy_setup's coefficient with the norm hardware */
static int unit_material_list(const sc_light_config* cfg, const sc_light_material* m, wlist* w) {
  const int specular = cfg->units != 0;
  const int any_n = (cfg->features & SC_LIGHT_FEAT_LOW_SHININESS) || !specular;
  const int low = any_n && m->shininess >= 0 && m->shininess < SC_LIGHT_FMT_N_MIN;
  const int fs_norm = (cfg->features & SC_LIGHT_FEAT_NORM) != 0;
  const int uf = cfg->unit_frac;
  int var, norm, e;
  uint32_t thr = 0, coef = 0;
  if (!low && (m->shininess < SC_LIGHT_FMT_N_MIN || m->shininess > SC_LIGHT_FMT_N_MAX)) return SC_LIGHT_ERR_RANGE;
  var = m->unit == SC_LIGHT_UNIT_DEFAULT ? cfg->first_unit : m->unit;
  if (specular && !(var >= 0 && var < 32 && ((cfg->units >> var) & 1u))) return SC_LIGHT_ERR_UNIT;
  if (!unit_known(var)) return SC_LIGHT_ERR_UNIT; /* Unit's constructor: a variant without a model */
  norm = fs_norm && m->norm_model >= 0;
  if (norm && m->norm_model >= SC_LIGHT_NUM_NORM_MODELS) return SC_LIGHT_ERR_UNIT; /* Unit::set_energy */
  if (norm && m->norm_kind != SC_LIGHT_COEF_FITTED && m->norm_kind != SC_LIGHT_COEF_CLASSICAL)
    return SC_LIGHT_ERR_RANGE;
  push(w, SC_LIGHT_REG_MAT_UNIT, (uint32_t)var);
  if (low) {
    /* n < 2^SC_LIGHT_LOW_N_BITS: the chain computes x^n; thr 0 and coef 1.0 */
    push(w, SC_LIGHT_REG_MAT_N, (uint32_t)m->shininess);
    push(w, SC_LIGHT_REG_MAT_THR, 0u);
    push(w, SC_LIGHT_REG_MAT_COEF, (uint32_t)1 << uf);
    return SC_LIGHT_OK;
  }
  if ((SC_LIGHT_UNITS_THR >> var) & 1u) {
    /* cs16_setup: thr = ceil(cos(6/√n)·2^UF) */
    const double ccr = cos(6.0 / sqrt((double)m->shininess));
    thr = (uint32_t)ceil(ldexp(ccr, uf));
  }
  if (norm) {
    /* energy_setup with the material's model and kind */
    if ((e = coef_code(uf, sc_light_energy_coef(m->norm_model, m->norm_kind, (double)m->shininess), &coef))) return e;
  } else if (fs_norm) {
    coef = (uint32_t)1 << uf; /* the norm hardware without normalisation: 1.0 */
  }
  push(w, SC_LIGHT_REG_MAT_N, (uint32_t)m->shininess);
  push(w, SC_LIGHT_REG_MAT_THR, thr);
  push(w, SC_LIGHT_REG_MAT_COEF, coef);
  return SC_LIGHT_OK;
}

static int colours_list(int F, const sc_light_material* m, uint32_t em, uint32_t am, uint32_t di, uint32_t sp,
                        wlist* w) {
  uint32_t c, code;
  int e;
  for (c = 0; c < 3; ++c) {
    if ((e = colour_code(F, m->emission[c], &code))) return e;
    push(w, em + c, code);
    if ((e = colour_code(F, m->ambient[c], &code))) return e;
    push(w, am + c, code);
    if ((e = colour_code(F, m->diffuse[c], &code))) return e;
    push(w, di + c, code);
    if ((e = colour_code(F, m->specular[c], &code))) return e;
    push(w, sp + c, code);
  }
  return SC_LIGHT_OK;
}

static int material_list(const sc_light_config* cfg, const sc_light_material* m, wlist* w) {
  const int e = unit_material_list(cfg, m, w);
  if (e) return e;
  return colours_list(cfg->frac, m, SC_LIGHT_REG_MAT_EMISSION, SC_LIGHT_REG_MAT_AMBIENT, SC_LIGHT_REG_MAT_DIFFUSE,
                      SC_LIGHT_REG_MAT_SPECULAR, w);
}

static int back_material_list(const sc_light_config* cfg, const sc_light_material* m, wlist* w) {
  return colours_list(cfg->frac, m, SC_LIGHT_REG_BACK_MAT_EMISSION, SC_LIGHT_REG_BACK_MAT_AMBIENT,
                      SC_LIGHT_REG_BACK_MAT_DIFFUSE, SC_LIGHT_REG_BACK_MAT_SPECULAR, w);
}

int sc_light_unit_material_writes(const sc_light_config* cfg, const sc_light_material* m, sc_light_writes* out) {
  wlist w;
  int e;
  if ((e = check_config(cfg)) || (e = check_out(out))) return e;
  if (!m) return SC_LIGHT_ERR_NULL;
  w.n = 0;
  if ((e = unit_material_list(cfg, m, &w))) return e;
  return commit(&w, out);
}

int sc_light_material_writes(const sc_light_config* cfg, const sc_light_material* m, sc_light_writes* out) {
  wlist w;
  int e;
  if ((e = check_config(cfg)) || (e = check_out(out))) return e;
  if (!m) return SC_LIGHT_ERR_NULL;
  w.n = 0;
  if ((e = material_list(cfg, m, &w))) return e;
  return commit(&w, out);
}

int sc_light_back_material_writes(const sc_light_config* cfg, const sc_light_material* back, sc_light_writes* out) {
  wlist w;
  int e;
  if ((e = check_config(cfg)) || (e = check_out(out))) return e;
  if (!back) return SC_LIGHT_ERR_NULL;
  w.n = 0;
  if ((e = back_material_list(cfg, back, &w))) return e;
  return commit(&w, out);
}

/* spot_cos_code: ⌈cos(cutoff)·2^VF⌉ as a VF+2-bit word, cos computed as sin((90 − cutoff)·π/180); 180: −2 */
static uint32_t spot_cos_code(int vf, double cutoff_deg) {
  const uint32_t m = SC_LIGHT_MASK(SC_LIGHT_FMT_SPOT_COS_BITS(0, vf));
  double c;
  int64_t code;
  if (cutoff_deg == 180.0) return ((uint32_t)1 << (vf + 1)) & m;
  c = sin((90.0 - cutoff_deg) * (acos(-1.0) / 180.0));
  code = (int64_t)ceil(ldexp(c, vf));
  return (uint32_t)code & m;
}

static int light_list(const sc_light_config* cfg, int j, const sc_light_light* lp, wlist* w) {
  const int F = cfg->frac;
  const uint32_t base = (uint32_t)j * SC_LIGHT_STRIDE;
  const uint32_t pmask = SC_LIGHT_MASK(SC_LIGHT_FMT_POSITION_BITS(F, 0));
  int kind, e;
  uint32_t c, code;
  if (j < 0 || j >= cfg->num_lights) return SC_LIGHT_ERR_INDEX;
  if (!(lp->spot_cutoff == 180.0 || (lp->spot_cutoff >= 0.0 && lp->spot_cutoff <= 90.0))) return SC_LIGHT_ERR_RANGE;
  if (lp->spot_exponent < SC_LIGHT_FMT_SPOT_EXPONENT_MIN || lp->spot_exponent > SC_LIGHT_FMT_SPOT_EXPONENT_MAX)
    return SC_LIGHT_ERR_RANGE;
  /* without an explicit kind: the slot's only kind; else directional for w = 0; for w != 0 spot when the cutoff
   * is not 180, else point with attenuation where the slot can take it, else point */
  kind = slot_kind(cfg, j);
  if (lp->kind != SC_LIGHT_KIND_AUTO) kind = lp->kind;
  else if (lp->position[3] == 0.0 && slot_can(cfg, j, SC_LIGHT_KIND_DIRECTIONAL)) kind = SC_LIGHT_KIND_DIRECTIONAL;
  else if (lp->position[3] != 0.0 && lp->spot_cutoff != 180.0) kind = SC_LIGHT_KIND_SPOT;
  else if (lp->position[3] != 0.0 && slot_can(cfg, j, SC_LIGHT_KIND_POINT_ATT)) kind = SC_LIGHT_KIND_POINT_ATT;
  else if (lp->position[3] != 0.0 && slot_can(cfg, j, SC_LIGHT_KIND_POINT)) kind = SC_LIGHT_KIND_POINT;
  if (!slot_can(cfg, j, kind)) return SC_LIGHT_ERR_KIND;
  push(w, base + SC_LIGHT_REG_LIGHT_MODE,
       (lp->enabled ? SC_LIGHT_LIGHT_MODE_ENABLE_MASK : 0u) | ((uint32_t)kind << SC_LIGHT_LIGHT_MODE_KIND_SHIFT));
  if (kind == SC_LIGHT_KIND_DIRECTIONAL) {
    if (lp->position[3] != 0.0) return SC_LIGHT_ERR_KIND;
    if ((e = push_unit_direction(w, base + SC_LIGHT_REG_LIGHT_POSITION, F, lp->position, pmask))) return e;
  } else {
    if (lp->position[3] == 0.0) return SC_LIGHT_ERR_KIND;
    for (c = 0; c < 3; ++c) {
      int64_t p;
      if ((e = pos_code(F, lp->position[c] / lp->position[3], &p))) return e;
      push(w, base + SC_LIGHT_REG_LIGHT_POSITION + c, (uint32_t)p & pmask);
    }
  }
  for (c = 0; c < 3; ++c) {
    if ((e = colour_code(F, lp->ambient[c], &code))) return e;
    push(w, base + SC_LIGHT_REG_LIGHT_AMBIENT + c, code);
    if ((e = colour_code(F, lp->diffuse[c], &code))) return e;
    push(w, base + SC_LIGHT_REG_LIGHT_DIFFUSE + c, code);
    if ((e = colour_code(F, lp->specular[c], &code))) return e;
    push(w, base + SC_LIGHT_REG_LIGHT_SPECULAR + c, code);
  }
  if (lp->spot_cutoff != 180.0 && kind != SC_LIGHT_KIND_SPOT) return SC_LIGHT_ERR_KIND;
  if (has_att(kind)) {
    uint32_t kc, kl, kq;
    if ((e = attc_code(F, lp->kc, &kc)) || (e = attc_code(F, lp->kl, &kl)) || (e = attc_code(F, lp->kq, &kq)))
      return e;
    if (kc == 0 && kl == 0 && kq == 0) return SC_LIGHT_ERR_ATTENUATION;
    push(w, base + SC_LIGHT_REG_LIGHT_KC, kc);
    push(w, base + SC_LIGHT_REG_LIGHT_KL, kl);
    push(w, base + SC_LIGHT_REG_LIGHT_KQ, kq);
  }
  if (kind == SC_LIGHT_KIND_SPOT) {
    if ((e = push_unit_direction(w, base + SC_LIGHT_REG_LIGHT_SPOT_DIRECTION, F, lp->spot_direction,
                                 SC_LIGHT_MASK(SC_LIGHT_FMT_DIRECTION_BITS(F, 0)))))
      return e;
    push(w, base + SC_LIGHT_REG_LIGHT_SPOT_COS, spot_cos_code(cfg->unit_frac, lp->spot_cutoff));
    /* cutoff 180 on a spot slot: exponent 0 (with the smallest cos the factor is 1 everywhere) */
    push(w, base + SC_LIGHT_REG_LIGHT_SPOT_EXPONENT, lp->spot_cutoff == 180.0 ? 0u : (uint32_t)lp->spot_exponent);
  }
  return SC_LIGHT_OK;
}

int sc_light_light_writes(const sc_light_config* cfg, int j, const sc_light_light* l, sc_light_writes* out) {
  wlist w;
  int e;
  if ((e = check_config(cfg)) || (e = check_out(out))) return e;
  if (!l) return SC_LIGHT_ERR_NULL;
  w.n = 0;
  if ((e = light_list(cfg, j, l, &w))) return e;
  return commit(&w, out);
}

static int light_off_list(const sc_light_config* cfg, int j, wlist* w) {
  if (j < 0 || j >= cfg->num_lights) return SC_LIGHT_ERR_INDEX;
  push(w, (uint32_t)j * SC_LIGHT_STRIDE + SC_LIGHT_REG_LIGHT_MODE, 0u);
  return SC_LIGHT_OK;
}

int sc_light_light_off_writes(const sc_light_config* cfg, int j, sc_light_writes* out) {
  wlist w;
  int e;
  if ((e = check_config(cfg)) || (e = check_out(out))) return e;
  w.n = 0;
  if ((e = light_off_list(cfg, j, &w))) return e;
  return commit(&w, out);
}

/* light_reset_writes: GL's initial light j (diffuse and specular 1 for light 0 only; position (0, 0, 1)) as the
 * richest kind the slot takes, then the mode word 0 */
int sc_light_light_reset_writes(const sc_light_config* cfg, int j, sc_light_writes* out) {
  wlist w;
  sc_light_light lp;
  int e, c;
  if ((e = check_config(cfg)) || (e = check_out(out))) return e;
  if (j < 0 || j >= cfg->num_lights) return SC_LIGHT_ERR_INDEX;
  sc_light_light_defaults(&lp);
  lp.enabled = 0;
  if (j != 0)
    for (c = 0; c < 3; ++c) lp.diffuse[c] = lp.specular[c] = 0;
  lp.position[3] = 1;
  if (slot_can(cfg, j, SC_LIGHT_KIND_SPOT)) lp.kind = SC_LIGHT_KIND_SPOT;
  else if (slot_can(cfg, j, SC_LIGHT_KIND_POINT_ATT)) lp.kind = SC_LIGHT_KIND_POINT_ATT;
  else if (slot_can(cfg, j, SC_LIGHT_KIND_POINT)) lp.kind = SC_LIGHT_KIND_POINT;
  else {
    lp.kind = SC_LIGHT_KIND_DIRECTIONAL;
    lp.position[3] = 0;
  }
  w.n = 0;
  if ((e = light_list(cfg, j, &lp, &w))) return e;
  w.w[0].data = 0; /* the mode word: off, kind 0 */
  return commit(&w, out);
}

static int colour_material_list(int mode, wlist* w) {
  if (mode != SC_LIGHT_CM_NONE && (mode < 0 || mode > (int)(SC_LIGHT_COLOUR_MATERIAL_MODE_MASK >>
                                                              SC_LIGHT_COLOUR_MATERIAL_MODE_SHIFT)))
    return SC_LIGHT_ERR_RANGE;
  push(w, SC_LIGHT_REG_COLOUR_MATERIAL,
       mode == SC_LIGHT_CM_NONE ? 0u
                                : SC_LIGHT_COLOUR_MATERIAL_ENABLE_MASK |
                                      ((uint32_t)mode << SC_LIGHT_COLOUR_MATERIAL_MODE_SHIFT));
  return SC_LIGHT_OK;
}

int sc_light_colour_material_writes(int mode, sc_light_writes* out) {
  wlist w;
  int e;
  if ((e = check_out(out))) return e;
  w.n = 0;
  if ((e = colour_material_list(mode, &w))) return e;
  return commit(&w, out);
}

int sc_light_state_writes(const sc_light_config* cfg, const sc_light_state* st, sc_light_writes* out) {
  wlist w;
  int e, j;
  if ((e = check_config(cfg)) || (e = check_out(out))) return e;
  if (!st) return SC_LIGHT_ERR_NULL;
  if (st->num_lights < 0 || st->num_lights > cfg->num_lights) return SC_LIGHT_ERR_INDEX;
  w.n = 0;
  if ((e = global_list(cfg, st->global_ambient, &st->modes, &w))) return e;
  if ((e = material_list(cfg, &st->material, &w))) return e;
  if (st->has_back_material && (e = back_material_list(cfg, &st->back_material, &w))) return e;
  if (cfg->features & SC_LIGHT_FEAT_COLOUR_MATERIAL) {
    if ((e = colour_material_list(st->colour_material, &w))) return e;
  } else if (st->colour_material != SC_LIGHT_CM_NONE) {
    return SC_LIGHT_ERR_FEATURE;
  }
  for (j = 0; j < cfg->num_lights; ++j)
    if ((e = j < st->num_lights ? light_list(cfg, j, &st->lights[j], &w) : light_off_list(cfg, j, &w))) return e;
  return commit(&w, out);
}
