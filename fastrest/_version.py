#: The installed fastrest version (a PEP 440 string).
__version__ = "0.3.0"
