"""The paper's search, exactly as reproduced: problem, bisectrix, expansion, A*-type search."""

__all__: list[str] = []
