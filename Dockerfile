# ShadeLab on Debian 12 with Mesa's llvmpipe (CPU rendering; a GPU is used when one is passed in).
#
#   docker build -t shadelab .                                                  the server (the default target)
#   docker build --target prairielearn-grader -t COURSE/shadelab-grader .       PrairieLearn's external grader
FROM debian:12 AS build
WORKDIR /src/shadelab
COPY tools/setup.sh tools/setup.sh
RUN tools/setup.sh && rm -rf /var/lib/apt/lists/*
COPY . .
RUN tools/build.sh -DSHADELAB_BUILD_TESTS=OFF -DSHADELAB_BUILD_BENCH=OFF

# PrairieLearn's external grader (docs/deploy.md, "On PrairieLearn"): only what grading needs (the
# binary, the libraries it loads, Mesa), the course's references warmed into the image as
# Gradescope's setup warms them, and the entrypoint PrairieLearn runs on /grade. No network at
# grading time: nothing is fetched.
FROM debian:12 AS prairielearn-grader
COPY tools/setup.sh /tmp/setup.sh
RUN /tmp/setup.sh runtime && rm -rf /var/lib/apt/lists/* /tmp/setup.sh
COPY --from=build /src/shadelab/build/shadelab /usr/local/bin/shadelab
COPY prairielearn/entrypoint /usr/local/bin/shadelab-prairielearn
# The built-in course's references; a course with its own profile warms it in an image built
# FROM this one (docs/deploy.md shows the four lines).
RUN SHADELAB_SOFTWARE=1 shadelab course warm --cache-dir /var/lib/shadelab/reference-store && chmod -R a+rX /var/lib/shadelab
# PrairieLearn's graders have no GPU: llvmpipe, the renderer the references were warmed with.
ENV SHADELAB_SOFTWARE=1
ENTRYPOINT ["/usr/local/bin/shadelab-prairielearn"]

# The server.
FROM build AS serve
EXPOSE 8889
ENTRYPOINT ["/src/shadelab/build/shadelab"]
CMD ["serve", "--host", "0.0.0.0", "--port", "8889"]
