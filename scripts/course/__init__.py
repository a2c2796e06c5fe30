"""The course's own Python library: what the scripts and tests share.

    course.exercises   the labs' exercises (their markers in the sources and shaders) and
                       tests/graded_exercises.txt: the one reader of both
"""
