"""The interactive page: a local server and the static files it serves.

:mod:`.engine` is the one place that talks to the deformation library (case
options, :class:`~sectiondeform.deform.Deformer`); :mod:`.server` is the
Starlette application; ``static/`` holds the page (plain JavaScript and SVG).
"""
