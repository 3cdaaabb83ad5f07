"""The benchmarks' shared library: the only package a benchmark imports; it
imports no benchmark."""
