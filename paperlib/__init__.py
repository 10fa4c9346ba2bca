"""paperlib: reference implementations of five papers on example-based synthesis of
drawings and textures (Hurtut 2009, Barla 2006, Kim 2009, Alvarez 2015, Simhon 2001).

See README.md for the paper -> module -> notebook table.
"""

__version__ = "0.1.0"
