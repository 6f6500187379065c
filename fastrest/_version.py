#: The installed fastrest version (a PEP 440 string).
__version__ = "0.2.0"
