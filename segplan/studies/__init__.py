"""Studies behind the book's chapters: helpers that measure the method, kept out of its core.

Each submodule serves one group of chapters and is imported by name (for example
``from segplan.studies.searches import run_searches``); nothing here is part of the stable
API in :data:`segplan.__all__`, and no module of the planning core imports from here.
"""

__all__: list[str] = []
