# SPDX-License-Identifier: Apache-2.0
"""shadecore — the bit-accurate fixed-point shading model from Python (docs/python.md).

NumPy in, NumPy out. Every function calls the C++ model the ``shadecore`` CLI calls (``shadecore::Unit``,
the golden references, ``energy_setup``/``energy_eval``, ``normalize3``, ``recip_att``, ``run_sweep``):
there is no second model. Arrays are converted once and handed to C++, which loops without the GIL;
bad input raises ``ValueError`` with the model's one-line message (the text the CLI prints after
``shadecore: error:``), a wrong dtype ``TypeError``.

    >>> import numpy as np, shadecore
    >>> shadecore.cs16(np.arange(65537), n=128)[-3:]
    array([65534, 65535, 65536])

Units (codes: signed integer input words, 1.0 = 2^F; or ``cos=`` real cos θ rounded to the nearest code
as ``shadecore eval --cos``): :func:`eval_unit` (any variant) and one function per variant —
:func:`cs16`, :func:`cs16_faithful`, :func:`cs16_compact`, :func:`schlick_div`, :func:`schlick_nr`,
:func:`schlick_iter`, :func:`table256`, :func:`table1024`. Width: ``config`` (narrow/default/wide) or
``frac``/``guard``; ``cutoff`` (cs16 and its forms); ``norm``/``coef`` (the sc_energy stage).
"""

import numpy as _np

from . import _core
from ._core import __version__

__all__ = [
    "__version__", "eval_unit", "setup", "cs16", "cs16_faithful", "cs16_compact", "schlick_div", "schlick_nr",
    "schlick_iter", "table256", "table1024", "cos_to_code", "code_to_cos", "format", "variants", "configs",
    "models", "sweep", "sweep_variants", "golden", "coef_value", "coef_code", "energy_eval", "normalize3",
    "normalize3_bound_ulp", "recip", "feature_sets", "LightCore", "render",
]


# ---------------------------------------------------------------------------- helpers
def _int_array(x, what):
    """x as an int64 array (any integer or bool dtype); floats are refused, not truncated."""
    a = _np.asarray(x)
    if a.dtype.kind not in "iub":
        raise TypeError(f"{what} must be integers (got dtype {a.dtype})")
    if a.dtype.kind == "u" and a.dtype.itemsize == 8 and a.size and int(a.max()) > _np.iinfo(_np.int64).max:
        raise ValueError(f"{what} {int(a.max())} does not fit a signed 64-bit integer")
    return a.astype(_np.int64, copy=False)


def _float_array(x, what):
    a = _np.asarray(x)
    if a.dtype.kind not in "iuf":
        raise TypeError(f"{what} must be real numbers (got dtype {a.dtype})")
    return a.astype(_np.float64, copy=False)


def _broadcast(data, n):
    """(data, n, shape): n stays one element when it is a scalar, else both are broadcast and made contiguous."""
    if n.size == 1 and n.ndim <= data.ndim:
        shape = _np.broadcast_shapes(data.shape, n.shape)
        if shape != data.shape:
            data = _np.broadcast_to(data, shape)
        return _np.ascontiguousarray(data), _np.ascontiguousarray(n.reshape(1)), shape
    data, n = _np.broadcast_arrays(data, n)
    return _np.ascontiguousarray(data), _np.ascontiguousarray(n), data.shape


def _outer(data, n):
    """(row, column) when data is one row ((m,) or (1, m)) and n one column ((k, 1), k > 1): the (n × data) grid,
    computed in C++ without materialising the broadcast inputs; else None."""
    if n.ndim == 2 and n.shape[1] == 1 and n.shape[0] > 1 and (data.ndim == 1 or (data.ndim == 2 and data.shape[0] == 1)):
        return _np.ascontiguousarray(data.reshape(-1)), _np.ascontiguousarray(n.reshape(-1))
    return None


def _config(config):
    return "" if config is None else str(config)


# ---------------------------------------------------------------------------- formats
def format(config=None, frac=None, guard=None):
    """The fixed-point format as a dict: frac F, guard G, in_min, in_max (the signed F+2-bit input word), one = 2^F."""
    return _core.format(_config(config), frac, guard)


def variants():
    """Every unit variant of config/configs.json."""
    return _core.variants()


def configs():
    """The named width configurations (narrow, default, wide)."""
    return _core.configs()


def models():
    """The six energy-normalisation models (phong, phong_mod, blinn, blinn_mod, blinn_ndf, blinn_hf)."""
    return _core.models()


def cos_to_code(cos, config=None, frac=None):
    """Real cos θ → the nearest input code (ties away from zero), as ``shadecore eval --cos``."""
    return _core.cos_to_code(_np.ascontiguousarray(_float_array(cos, "cos")), _config(config), frac)


def code_to_cos(codes, config=None, frac=None):
    """Input codes → the real value code / 2^F, clamped to [0, 1] as the unit's input stage clamps it."""
    f = format(config, frac)
    return _np.ldexp(_np.clip(_int_array(codes, "codes"), 0, f["one"]).astype(_np.float64), -f["frac"])


# ---------------------------------------------------------------------------- units
def eval_unit(variant, codes=None, n=None, *, cos=None, config=None, frac=None, guard=None, cutoff=None, norm=None,
              coef=None):
    """Outputs (int64 codes, 1.0 = 2^F) of `variant` for every input code — ``shadecore eval``'s out_spec_o.

    codes: signed input words (any integer array, each in [-2^(F+1), 2^(F+1)-1]); or cos=: real cos θ values.
    n: the specular exponent, 16..1024: one value, or an array broadcast against the inputs.
    norm: an energy model name or 'all' (the sc_energy stage after the unit, as ``eval --norm``); coef:
    'fitted' (default) or 'classical'.
    """
    if n is None:
        raise TypeError("n is required (the specular exponent, 16..1024)")
    if (codes is None) == (cos is None):
        raise TypeError("give exactly one of codes and cos=")
    if cos is not None:
        codes = cos_to_code(cos, config, frac)
    data, nn = _int_array(codes, "codes"), _int_array(n, "n")
    grid = _outer(data, nn)
    if grid:
        return _core.unit_eval_outer(str(variant), *grid, _config(config), frac, guard, cutoff, norm, coef)
    data, nn, shape = _broadcast(data, nn)
    out = _core.unit_eval(str(variant), data, nn, _config(config), frac, guard, cutoff, norm, coef)
    return out.reshape(shape)


def setup(variant, n, *, config=None, frac=None, guard=None, cutoff=None, norm=None, coef=None):
    """The material words per n (dict of arrays thr = mat_thr_i, coef = mat_coef_i) and the unit's latency."""
    nn = _np.ascontiguousarray(_int_array(n, "n"))
    return _core.unit_setup(str(variant), nn, _config(config), frac, guard, cutoff, norm, coef)


def _unit(name):
    def f(codes=None, n=None, *, cos=None, config=None, frac=None, guard=None, cutoff=None, norm=None, coef=None):
        return eval_unit(name, codes, n, cos=cos, config=config, frac=frac, guard=guard, cutoff=cutoff, norm=norm,
                         coef=coef)
    f.__name__ = f.__qualname__ = name
    f.__doc__ = (f"The {name} unit's outputs for every input code (or cos=), at exponent n: "
                 f"eval_unit('{name}', ...). See eval_unit for the arguments.")
    return f


cs16 = _unit("cs16")
cs16_faithful = _unit("cs16_faithful")
cs16_compact = _unit("cs16_compact")
schlick_div = _unit("schlick_div")
schlick_nr = _unit("schlick_nr")
schlick_iter = _unit("schlick_iter")
table256 = _unit("table256")
table1024 = _unit("table1024")


# ---------------------------------------------------------------------------- golden references
class _Golden:
    """Double-precision golden references (shadecore/analysis/golden.hpp), c = cos θ as reals, n broadcast."""

    @staticmethod
    def _map(fn, c, n, *extra):
        data, nn = _float_array(c, "c"), _int_array(n, "n")
        grid = _outer(data, nn)
        if grid:
            return fn(*grid, *extra, True)
        data, nn, shape = _broadcast(data, nn)
        return fn(data, nn, *extra, False).reshape(shape)

    def cos_pow(self, c, n):
        """Phong's cos^n θ (any n >= 0)."""
        return self._map(_core.golden_cos_pow, c, n)

    def cs16(self, c, n, cutoff="theta_cr"):
        """cs16 in double with the θcr cut-off (or cutoff='sign_clamp')."""
        return self._map(_core.golden_cs16, c, n, str(cutoff))

    def schlick(self, c, n):
        """Schlick's t / (n − n·t + t)."""
        return self._map(_core.golden_schlick, c, n)

    def variant(self, variant, c, n, cutoff="theta_cr"):
        """The double twin of a variant, the function ``shadecore sweep`` measures the quantisation against
        (cs16 and its forms: cs16; Schlick units: schlick; table units: the double table lerp)."""
        return self._map(lambda c_, n_, cut, outer: _core.golden_variant(str(variant), c_, n_, cut, outer), c, n,
                         str(cutoff))

    def theta_cr(self, n):
        """θcr(n) = 6/√n in radians."""
        return _core.theta_cr(_np.ascontiguousarray(_int_array(n, "n")))


golden = _Golden()


# ---------------------------------------------------------------------------- energy normalisation
def coef_value(model, n, kind="fitted"):
    """coef(n) in double for an energy model ('fitted': the paper's (a·n + b)/(k·π); 'classical')."""
    return _core.coef_value(str(model), _np.ascontiguousarray(_int_array(n, "n")), str(kind))


def coef_code(model, n, kind="fitted", frac=16, int_bits=8):
    """mat_coef_i: coef(n) rounded half up to an unsigned word with int_bits integer and frac fraction bits."""
    return _core.coef_code(str(model), _np.ascontiguousarray(_int_array(n, "n")), str(kind), int(frac), int(int_bits))


def energy_eval(spec, coef, frac=16, int_bits=8):
    """sc_energy: round_half_up(spec · coef / 2^F) for unit outputs spec (<= 2^F) and coefficient codes."""
    s = _np.ascontiguousarray(_int_array(spec, "spec"))
    c = _int_array(coef, "coef")
    if c.size != 1:
        s, c = _np.broadcast_arrays(s, c)
        s = _np.ascontiguousarray(s)
    return _core.energy_eval(s, _np.ascontiguousarray(c.reshape(-1)), int(frac), int(int_bits)).reshape(s.shape)


# ---------------------------------------------------------------------------- lighting operators
def normalize3(v, frac=16):
    """sc_normalize: v / |v| for integer vectors in the last axis (length 3), each component rounded half up to
    frac fraction bits (1.0 = 2^frac); v = 0 gives 0."""
    return _core.normalize3(_np.ascontiguousarray(_int_array(v, "v")), int(frac))


def normalize3_bound_ulp(frac):
    """The stated bound of normalize3 in output ulps (0.55 up to F = 22, else 0.70)."""
    return _core.normalize3_bound_ulp(int(frac))


def recip(q, frac=16):
    """sc_recip: the attenuation 1/q for q >= 0 with frac fraction bits, rounded half up, saturated at 2^(F+8) − 1."""
    return _core.recip(_np.ascontiguousarray(_int_array(q, "q")), int(frac))


# ---------------------------------------------------------------------------- sweep
def sweep_variants():
    """The variants ``shadecore sweep`` (and :func:`sweep`) accepts."""
    return _core.sweep_variants()


def sweep(variant="cs16", n="16..1024", *, config=None, frac=None, guard=None, cutoff=None, threads=0):
    """The exhaustive error sweep of ``shadecore sweep`` (the same engine, run_sweep): every n in the range × every
    input code in [0, 2^F]. Returns a dict: per-n NumPy columns named as the CLI's --csv header (n, approx_max,
    approx_max_code, ..., nonzero_codes), the overall extremes 'approx', 'quant_ulp', 'total' ({'max': {'value',
    'n', 'code'}, 'min': ...}), and evaluations, seconds, threads. n: 'LO..HI', 'N', an int or a (lo, hi) pair.
    """
    if isinstance(n, (tuple, list)):
        if len(n) != 2:
            raise ValueError("n: give 'LO..HI', N or a (lo, hi) pair")
        n = f"{int(n[0])}..{int(n[1])}"
    elif isinstance(n, (int, _np.integer)):
        n = str(int(n))
    return _core.sweep(str(variant), str(n), _config(config), frac, guard, cutoff, int(threads))


# ---------------------------------------------------------------------------- the lighting core
def feature_sets():
    """The named feature sets of config/configs.json."""
    return _core.feature_sets()


def _rows3(x, what):
    a = _int_array(x, what)
    if a.ndim == 1 and a.size == 3:
        a = a.reshape(1, 3)
    return _np.ascontiguousarray(a)


class LightCore:
    """The lighting core's bit-accurate model (LightCore, cmodel/include/shadecore/light.hpp) for a feature set — a
    name of config/configs.json, a JSON file, or a dict with the keys of a feature-set file — and the register state it
    holds. Program it with register writes (:meth:`write`, as the RTL and the handoff vectors) or from a GL-like state
    dict (:meth:`program`, through the renderer's host-side helpers light_writes/material_writes/...), then shade
    arrays of fragments with :meth:`eval` (fixed point) or :meth:`eval_double` (the double reference)."""

    def __init__(self, features="full"):
        import json
        if isinstance(features, dict):
            self._c = _core.LightCore(json.dumps(features), True)
        else:
            self._c = _core.LightCore(str(features), False)

    name = property(lambda self: self._c.name, doc="the feature set's name ('custom' for an unnamed dict or file)")
    summary = property(lambda self: self._c.summary, doc="one line: slots, kinds, terms, unit, widths")
    key = property(lambda self: self._c.key, doc="the build-cache key of the Verilated core for this set")
    frac = property(lambda self: self._c.frac, doc="F: colour, normal and position fraction bits")
    unit_frac = property(lambda self: self._c.unit_frac, doc="F + spec_guard: the specular path's fraction bits")
    num_lights = property(lambda self: self._c.num_lights, doc="light slots")

    def write(self, addr, data):
        """Register writes in order (reg_addr_i, reg_data_i); returns how many hit a register."""
        a = _np.ascontiguousarray(_int_array(addr, "addr").reshape(-1))
        d = _np.ascontiguousarray(_int_array(data, "data").reshape(-1))
        return self._c.write(a, d)

    def program(self, state):
        """Program the registers from a GL-like state dict and return the writes as (addr, data) arrays. Keys (all
        optional): global_ambient [r, g, b]; modes {local_viewer, phong, normalize, separate_specular, two_side};
        material {emission, ambient, diffuse, specular, shininess, unit, norm, coef}; back_material {...};
        colour_material 'none'|'emission'|'ambient'|'diffuse'|'specular'|'ambient_and_diffuse'; lights [{position
        [x, y, z, w], ambient, diffuse, specular, kc, kl, kq, spot_direction, spot_cutoff, spot_exponent, enabled,
        kind}] (slots beyond the list are switched off). Defaults are GL's."""
        import json
        w = self._c.program(json.dumps(state))
        a = _np.array([x[0] for x in w], dtype=_np.int64)
        d = _np.array([x[1] for x in w], dtype=_np.int64)
        return a, d

    def _frag(self, n, p, colour, back):
        n = _rows3(n, "n")
        p = _rows3(p, "p")
        colour = None if colour is None else _rows3(colour, "colour")
        if back is not None:
            back = _np.ascontiguousarray(_int_array(back, "back").reshape(-1))
        return n, p, colour, back

    def eval(self, n, p, colour=None, back=None):
        """Shade fragments: n, p (k, 3) signed codes (normal 1.0 = 2^F; position with F fraction bits in [-128, 128)),
        colour (k, 3) fragment colour codes (colour_material), back (k,) facing bits. Returns {'colour': (k, 3),
        'secondary': (k, 3)} output codes (out_r/g/b_o, out_sr/sg/sb_o)."""
        return self._c.eval(*self._frag(n, p, colour, back))

    def eval_double(self, n, p, colour=None, back=None, reference="exact"):
        """The double-precision reference of the same fragments (reference 'exact': cos^n; 'variant': the unit's
        function in double); colours in [0, 1]."""
        return self._c.eval_double(*self._frag(n, p, colour, back), str(reference))

    def fragment_codes(self, n, p):
        """Eye-space doubles (k, 3) → (normal codes, position codes) as the renderer rounds them."""
        return self._c.fragment_codes(_np.ascontiguousarray(_float_array(n, "n").reshape(-1, 3)),
                                      _np.ascontiguousarray(_float_array(p, "p").reshape(-1, 3)))


# ---------------------------------------------------------------------------- render
def render(scene, size=None, *, full_core=False, lanes=1, share=1):
    """A scene file (docs/scenes.md) through the host rasteriser and the lighting core's C model, as ``shadecore
    render`` computes it (C model and references only; no RTL). size: (width, height) or 'WxH' (default: the scene's).
    Returns a dict of arrays, rows from the top: image (h, w, 3) colour codes (1.0 = 2^F, GL's colour sum),
    covered (h, w), exact and unit_double (h, w, 3) the double references in [0, 1] (cos^n; the unit's function),
    rgb8 and exact_rgb8 (the 8-bit pixels of cmodel.png and exact.png), frac, cores (the feature set of each core)."""
    import os
    if isinstance(size, str):
        w, sep, h = size.partition("x")
        if not sep or not w.isdigit() or not h.isdigit():
            raise ValueError(f"size: malformed '{size}' (expected WxH, e.g. 64x64)")
        size = (int(w), int(h))
    elif size is not None:
        size = (int(size[0]), int(size[1]))
    return _core.render(os.fspath(scene), size, bool(full_core), int(lanes), int(share))
