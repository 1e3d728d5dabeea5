# ShadeLab on Debian 12 with Mesa's llvmpipe (CPU rendering; a GPU is used when one is passed in).
FROM debian:12
WORKDIR /src/shadelab
COPY tools/setup.sh tools/setup.sh
RUN tools/setup.sh && rm -rf /var/lib/apt/lists/*
COPY . .
RUN tools/build.sh -DSHADELAB_BUILD_TESTS=OFF -DSHADELAB_BUILD_BENCH=OFF
EXPOSE 8889
ENTRYPOINT ["/src/shadelab/build/shadelab"]
CMD ["serve", "--host", "0.0.0.0", "--port", "8889"]
