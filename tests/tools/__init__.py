# Makes tests/tools a package so `python3 -m unittest discover -s tests/tools -t .` finds it.
