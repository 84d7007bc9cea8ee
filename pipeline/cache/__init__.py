"""The on-disk cache: one layer for meshes, FE tables, groove bodies, contact cycles,
root-stress tables and figures.

* ``folder`` - where the cache lives (``GEARPIPE_CACHE_DIR``, ``meshes/`` of a checkout, the
  user cache folder) and :class:`~pipeline.cache.folder.Cache`, the one object every step
  that caches takes (its folder, or off).
* ``entries`` - ``.npz`` entries keyed by their inputs and by the source of the code that
  produces them, the key stored inside and checked on read (a mismatch or a damaged file
  is a warning and a rebuild). Figures carry the same kind of key in their PNG
  (:mod:`pipeline.viz.figure_cache`).
"""

from pipeline.cache.folder import Cache, CacheWarning

__all__ = ["Cache", "CacheWarning"]
