"""The study kinds, one package each: ``benchmark`` (Tables 3, 5), ``planning`` (Table 6),
``suite`` (BBOB via ioh, CEC 2017/2022 under COCO's protocol) and ``arena`` (generated scene
families x planners).

A kind imports the harness (:mod:`mawdo.experiments.protocol`, ``plans``, ``rows``, ``store``,
``runner``, ``stats``, ``tables``) and never another kind; it registers itself with
:func:`~mawdo.experiments.protocol.register_kind` when its package is imported, and
:mod:`mawdo.experiments` imports each built-in kind with one line.
"""
